// occlusion_policy.h: which frames cull by occlusion when the user leaves it to the renderer.
// Two-pass occlusion culling (docs/design.md, "Occlusion culling") costs a frame a fixed amount whatever
// it hides: the depth pyramid, the early pass's tests of everything against it, the late pass's steps.
// Where little is hidden (a scene seen from above, a few objects side by side) that is all it does, so
// the automatic policy runs two passes only while they hide a tenth of what a frame draws, and otherwise
// probes again every kOcclusionProbePeriod frames: a frame that leaves a pyramid, then a two-pass frame
// that tests against it. The picture is the same whichever frame runs which way; only time differs.
#pragma once

#include <algorithm>
#include <cstdint>

namespace vgeo {

enum class Occlusion { Off, On, Auto };

// How a frame that may cull by occlusion runs.
enum class OcclusionPlan {
  OnePass,             // selects and draws once
  OnePassThenPyramid,  // once, then builds the depth pyramid of its picture for the next frame's early pass
  TwoPass,             // early pass against the last pyramid, the pyramid, late pass against it
};

// Frames between probes while two passes do not pay: the probe's two frames cost about one frame's
// worth of the two passes' fixed cost, spread over this many (bench/occlusion.md).
constexpr uint32_t kOcclusionProbePeriod = 16;
// Two passes pay while they hide at least 1 / kOcclusionPaysAbove of what a frame draws: about what they
// cost a frame that hides nothing, on the H100 and on lavapipe (bench/occlusion.md).
constexpr uint64_t kOcclusionPaysAbove = 10;

class OcclusionPolicy {
 public:
  // The next frame's plan. The first two frames draw in one pass (`vgeo render` of a picture builds no
  // pyramid nobody reads); the first probe is the fourth frame.
  OcclusionPlan next(bool pyramidMade) const {
    if ((pays_ || untilProbe_ == 0) && pyramidMade) return OcclusionPlan::TwoPass;
    return untilProbe_ <= 1 ? OcclusionPlan::OnePassThenPyramid : OcclusionPlan::OnePass;
  }
  // What a frame of `plan` did. For two passes: the late pass's hidden instances, BVH nodes and groups,
  // and clusters (each hidden instance or node counted as the clusters an instance draws on average), and
  // the clusters drawn and instances visible in both passes.
  void record(OcclusionPlan plan, uint64_t hiddenInstancesAndNodes, uint64_t hiddenClusters, uint64_t drawnClusters,
              uint64_t visibleInstances) {
    if (plan != OcclusionPlan::TwoPass) {
      if (untilProbe_ > 0) untilProbe_--;
      return;
    }
    const uint64_t perInstance = visibleInstances ? std::max<uint64_t>(drawnClusters / visibleInstances, 1) : 1;
    const uint64_t hidden = hiddenClusters + hiddenInstancesAndNodes * perInstance;
    pays_ = hidden > 0 && hidden * kOcclusionPaysAbove >= drawnClusters;
    if (!pays_) untilProbe_ = kOcclusionProbePeriod;
  }
  bool pays() const { return pays_; }

 private:
  bool pays_ = false;
  uint32_t untilProbe_ = 3;  // frames until the probe's two-pass frame (the one before leaves the pyramid)
};

}  // namespace vgeo
