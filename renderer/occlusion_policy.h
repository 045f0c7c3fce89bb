// occlusion_policy.h: which frames cull by occlusion when the user leaves it to the renderer.
// Two-pass occlusion culling (docs/design.md, "Occlusion culling") costs a frame a fixed amount whatever
// it hides: the depth pyramid, the early pass's tests of everything against it, the late pass's steps.
// What it saves is what the hidden part would have cost to select, cull and rasterize. Neither is known
// from counts alone (a hidden cluster of 2 triangles saves less than one of 128; on one device the fixed
// part is 0.07 ms, on another 30 ms), so the automatic policy decides by the frames' own measured times:
// two passes while a two-pass frame takes no longer than the last one-pass frame did, one pass otherwise.
// Each way is measured again every kOcclusionProbePeriod frames: while one pass wins, a frame that leaves
// a pyramid and a two-pass frame against it; while two win, one frame in one pass (it leaves a pyramid
// too, so the next frame's early pass has the depth of the frame before it). The picture is the same
// whichever frame runs which way; only time differs.
#pragma once

#include <cstdint>

namespace vgeo {

enum class Occlusion { Off, On, Auto };

// How a frame that may cull by occlusion runs.
enum class OcclusionPlan {
  OnePass,             // selects and draws once
  OnePassThenPyramid,  // once, then builds the depth pyramid of its picture for the next frame's early pass
  TwoPass,             // early pass against the last pyramid, the pyramid, late pass against it
};

// Frames between measurements of the way not taken. A probe costs about one frame's difference between
// the two ways (plus a pyramid while one pass wins), spread over this many frames: a few per cent at
// most of a frame where the losing way costs 1.5x (bench/occlusion.md).
constexpr uint32_t kOcclusionProbePeriod = 16;

class OcclusionPolicy {
 public:
  // The next frame's plan. The first two frames draw in one pass (`vgeo render` of a picture builds no
  // pyramid nobody reads); the third leaves a pyramid, the fourth runs two passes against it.
  OcclusionPlan next(bool pyramidMade) const {
    if (twoPassWins_)
      return untilProbe_ == 0 || !pyramidMade ? OcclusionPlan::OnePassThenPyramid : OcclusionPlan::TwoPass;
    if (untilProbe_ == 0 && pyramidMade) return OcclusionPlan::TwoPass;
    return untilProbe_ <= 1 ? OcclusionPlan::OnePassThenPyramid : OcclusionPlan::OnePass;
  }
  // What a frame of `plan` took: the whole frame, and of it the depth pyramid's build (a one-pass frame
  // that leaves a pyramid counts as a one-pass frame without it).
  void record(OcclusionPlan plan, double frameMs, double pyramidMs) {
    const bool twoPass = plan == OcclusionPlan::TwoPass;
    (twoPass ? twoPassMs_ : onePassMs_) = twoPass ? frameMs : frameMs - pyramidMs;
    (twoPass ? measuredTwoPass_ : measuredOnePass_) = true;
    if (twoPass != twoPassWins_)
      untilProbe_ = kOcclusionProbePeriod;  // the way not taken was measured: the next probe is a period away
    else if (untilProbe_ > 0)
      untilProbe_--;
    twoPassWins_ = measuredOnePass_ && measuredTwoPass_ && twoPassMs_ <= onePassMs_;
  }
  bool twoPassWins() const { return twoPassWins_; }

 private:
  bool twoPassWins_ = false, measuredOnePass_ = false, measuredTwoPass_ = false;
  double onePassMs_ = 0.0, twoPassMs_ = 0.0;  // the last frame of each way
  uint32_t untilProbe_ = 3;                   // frames until the way not taken is measured again
};

}  // namespace vgeo
