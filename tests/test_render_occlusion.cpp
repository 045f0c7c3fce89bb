// test_render_occlusion.cpp: two-pass occlusion culling on lavapipe (or any device) with the validation
// layer, on a dense forest of the shipped cage: along a camera path that moves, turns and jumps, the
// picture with occlusion culling equals the picture without, frame by frame; what it draws is a subset of
// the CPU reference cut and holds every cluster the picture shows; it does hide things from the ground;
// and a frozen cut keeps its occlusion while the camera moves.
#include <algorithm>

#include "../common/vgeo_file.h"
#include "../renderer/gpu_renderer.h"
#include "../renderer/image.h"
#include "render_util.h"
#include "test_util.h"

namespace vgeo {
namespace {

constexpr uint32_t kW = 320, kH = 200;

class RenderOcclusion : public test::GpuSuite {
 protected:
  static void SetUpTestSuite() {
    openSuite("vgeo_render_occlusion_tests");
    writeVgeo(test::build(test::asset("horned_cube.obj"), 2), *dir + "/horned.vgeo");
    forest = new RenderScene(makeBenchScene(loadRenderScene(*dir + "/horned.vgeo"), 144, BenchLayout::Forest, 7));
  }
  static void TearDownTestSuite() {
    delete forest;
    forest = nullptr;
    closeSuite();
  }

  // From the ground just outside the forest's near (-z) edge, `forward` of its depth in and turned by `yaw`.
  static Camera ground(float forward, float yaw) {
    const float depth = forest->boxMax.z - forest->boxMin.z, r = forest->data.geometries[0].boundsSphere.w;
    Camera c;
    c.eye = glm::vec3(forest->bounds.x + 0.3f * r, forest->bounds.y, forest->boxMin.z - r + forward * depth);
    c.target = c.eye + glm::vec3(std::sin(yaw), -0.05f, std::cos(yaw));
    return c;
  }
  static Camera above() {
    Camera c;
    c.target = glm::vec3(forest->bounds);
    c.eye = c.target + glm::vec3(0.2f, 1.2f, -0.8f) * forest->bounds.w;
    return c;
  }
  static FrameSettings settings(const Camera& camera, bool occlusion) {
    FrameSettings s = test::frameSettings(*forest, camera, 1.0f, kW, kH);
    s.occlusion = occlusion ? Occlusion::On : Occlusion::Off;
    return s;
  }
  static FrameResult complete(GpuRenderer& renderer, const FrameSettings& s) {
    FrameResult r = renderer.renderFrame(s);
    for (int i = 0; i < 8 && !r.complete; i++) r = renderer.renderFrame(s);
    EXPECT_TRUE(r.complete);
    return r;
  }

  // Whether every cluster the picture without occlusion culling shows (read pixel by pixel from its
  // visibility buffer) is among those drawn with it.
  static void expectShownAreDrawn(const FrameResult& with, const FrameResult& without, size_t pose) {
    auto key = [](const CutEntry& e) { return uint64_t(e.instance) << 32 | e.cluster; };
    std::vector<uint64_t> drawn;
    for (const CutEntry& e : with.drawList) drawn.push_back(key(e));
    std::sort(drawn.begin(), drawn.end());
    for (const CutEntry& e : without.pixelClusters)
      EXPECT_TRUE(std::binary_search(drawn.begin(), drawn.end(), key(e)))
          << "pose " << pose << ": instance " << e.instance << " cluster " << e.cluster << " shows but was not drawn";
  }

  static inline RenderScene* forest = nullptr;
};

TEST_F(RenderOcclusion, PictureEqualsThePictureWithoutAlongAPath) {
  // Moving in and turning, a jump cut to above and back, a close pose (patches) and the first frame.
  const std::vector<Camera> path = {
      ground(0.0f, 0.0f),  ground(0.03f, 0.1f), ground(0.06f, 0.25f), ground(0.09f, 0.4f), above(),
      ground(0.1f, -0.3f), ground(0.12f, 0.0f), ground(0.0f, 0.05f)};
  // Both rasterizers; instance culling one lane an instance, spread over lanes, and in the traversal.
  struct Config {
    Raster raster;
    uint32_t cullLanes;
    InstanceCulling culling;
  };
  for (const Config& config :
       {Config{Raster::Auto, 0, InstanceCulling::Auto}, Config{Raster::Software, 1, InstanceCulling::Pass},
        Config{Raster::Auto, VGEO_CULL_INSTANCE_LANES, InstanceCulling::Pass},
        Config{Raster::Auto, VGEO_CULL_INSTANCE_LANES, InstanceCulling::InTraversal}}) {
    GpuRenderer occluding(*vk, *forest, kW, kH), plain(*vk, *forest, kW, kH);
    uint64_t hidden = 0;
    uint32_t drawnWith = 0, drawnWithout = 0;
    for (size_t i = 0; i < path.size(); i++) {
      for (uint32_t mode : {VGEO_MODE_LIT, VGEO_MODE_CLUSTER}) {
        if (mode != VGEO_MODE_LIT && config.culling != InstanceCulling::Auto) continue;
        FrameSettings with = settings(path[i], true), without = settings(path[i], false);
        with.raster = without.raster = config.raster;
        with.cullLanes = without.cullLanes = config.cullLanes;
        with.instanceCulling = without.instanceCulling = config.culling;
        with.mode = without.mode = mode;
        without.readPixelClusters = config.raster == Raster::Software;  // every pixel in the visibility buffer
        const FrameResult a = complete(occluding, with), b = complete(plain, without);
        if (without.readPixelClusters) {
          EXPECT_TRUE(b.drewIntoVisibility);
          expectShownAreDrawn(a, b, i);
        }
        ASSERT_TRUE(a.occlusion);
        EXPECT_EQ(a.culledInTraversal, config.culling == InstanceCulling::InTraversal);
        EXPECT_TRUE(a.rgba == b.rgba) << "pose " << i << " mode " << mode << " raster " << int(config.raster)
                                      << " culling " << int(config.culling);
        std::string difference;
        EXPECT_TRUE(compareCuts(selectSceneCut(*forest, with.cullView, 1.0f), a.drawList, difference, true))
            << "pose " << i << ": " << difference;
        if (mode != VGEO_MODE_LIT) continue;
        hidden += a.counters.occludedInstances + a.counters.occludedNodes + a.counters.occludedClusters;
        drawnWith += a.counters.drawCount;
        drawnWithout += b.counters.drawCount;
      }
    }
    // The test can fail only if something was hidden: from the ground parts of the forest are (the
    // first frame, with no pyramid from a frame before, hides nothing).
    EXPECT_GT(hidden, 0u);
    EXPECT_LT(drawnWith, drawnWithout);
  }
}

TEST_F(RenderOcclusion, EveryClusterThePictureShowsIsDrawn) {
  // The clusters the picture without occlusion culling shows, pixel by pixel (every pixel in the
  // visibility buffer: the compute rasterizers and the bare render pass), are among those drawn with it.
  GpuRenderer occluding(*vk, *forest, kW, kH), plain(*vk, *forest, kW, kH);
  for (const Camera& camera : {ground(0.0f, 0.0f), ground(0.02f, 0.2f), ground(0.05f, -0.2f)}) {
    FrameSettings with = settings(camera, true), without = settings(camera, false);
    with.raster = without.raster = Raster::Software;
    without.readPixelClusters = true;
    complete(occluding, with);  // the first frame from a camera has no pyramid to test against
    const FrameResult a = complete(occluding, with), b = complete(plain, without);
    ASSERT_TRUE(b.drewIntoVisibility);
    ASSERT_GT(b.pixelClusters.size(), 10u);
    expectShownAreDrawn(a, b, 0);
    EXPECT_LT(a.drawList.size(), b.drawList.size());
  }
}

TEST_F(RenderOcclusion, FrozenCutKeepsItsOcclusion) {
  // Frozen at a ground camera, the cut stays the same while the picture moves: behind the first rows,
  // and above the forest, where the frozen camera's hidden instances come into sight.
  GpuRenderer renderer(*vk, *forest, kW, kH);
  const Camera frozen = ground(0.02f, 0.1f);
  std::vector<CutEntry> first;
  for (const Camera& camera : {ground(0.0f, 0.3f), above(), ground(0.3f, 1.2f), above()}) {
    FrameSettings s = settings(camera, true);
    s.cullView = makeView(frozen, kW, kH, forest->bounds);
    const FrameResult r = complete(renderer, s);
    std::string difference;
    EXPECT_TRUE(compareCuts(selectSceneCut(*forest, s.cullView, 1.0f), r.drawList, difference, true)) << difference;
    auto sorted = r.drawList;
    std::sort(sorted.begin(), sorted.end(), [](const CutEntry& x, const CutEntry& y) {
      return x.instance != y.instance ? x.instance < y.instance : x.cluster < y.cluster;
    });
    if (first.empty()) first = sorted;
    EXPECT_TRUE(sorted == first) << "the frozen cut changed";
  }
  EXPECT_LT(first.size(), selectSceneCut(*forest, makeView(frozen, kW, kH, forest->bounds), 1.0f).entries.size());
}

TEST_F(RenderOcclusion, AutoRunsTheWayItMeasuredFaster) {
  // Along a path from the ground (two passes hide most of the forest) to above (they hide little), Auto
  // runs each frame the way the frames it timed say is faster, measures the other way every period, and
  // every picture is the one without occlusion culling. The times are lavapipe's or the GPU's own, so the
  // test follows them rather than expecting either way to win.
  GpuRenderer automatic(*vk, *forest, kW, kH), plain(*vk, *forest, kW, kH);
  std::vector<Camera> path;
  for (int i = 0; i < 8; i++) path.push_back(ground(0.01f * float(i), 0.02f * float(i)));
  for (int i = 0; i < 2 * int(kOcclusionProbePeriod) + 6; i++) path.push_back(above());
  for (const Camera& camera : path) complete(automatic, settings(camera, false));  // lists grown, no policy step
  double onePassMs = -1.0, twoPassMs = -1.0;  // the last frame of each way, as the policy sees them
  uint32_t twoPass = 0, onePass = 0, sinceOtherWay = 0;
  for (size_t i = 0; i < path.size(); i++) {
    FrameSettings s = settings(path[i], false), without = s;
    s.occlusion = Occlusion::Auto;
    const FrameResult a = automatic.renderFrame(s), b = complete(plain, without);
    ASSERT_TRUE(a.complete) << "frame " << i;
    EXPECT_TRUE(a.rgba == b.rgba) << "frame " << i;
    if (i < 3) {
      EXPECT_FALSE(a.occlusion) << "frame " << i << ": the first three frames run one pass";
    }
    if (i == 3) {
      EXPECT_TRUE(a.occlusion) << "the fourth frame measures two passes";
    }
    // Past the first measurements, the frame runs the way that was faster last time (a probe of the
    // other way aside: at most one a period, and the frame before a two-pass probe leaves a pyramid).
    const bool twoPassWon = onePassMs >= 0.0 && twoPassMs >= 0.0 && twoPassMs <= onePassMs;
    if (i > 3 && a.occlusion != twoPassWon) {
      EXPECT_GE(sinceOtherWay, kOcclusionProbePeriod - 1) << "frame " << i << ": a probe within a period of the last";
      sinceOtherWay = 0;
    } else {
      sinceOtherWay++;
    }
    (a.occlusion ? twoPassMs : onePassMs) = a.occlusion ? a.frameMs : a.frameMs - a.pyramidMs;
    (a.occlusion ? twoPass : onePass)++;
  }
  // Over 46 frames each way was measured at least twice.
  EXPECT_GE(twoPass, 2u);
  EXPECT_GE(onePass, 2u);
}

TEST_F(RenderOcclusion, PyramidViewShowsDepthOnlyWhereThePictureHasIt) {
  // The pyramid view at level 1 (a texel a 2 x 2 block of pixels): a texel holds a depth only where all
  // four pixels show a surface, both as the late pass tests against it (two passes) and as a one-pass
  // frame leaves it for the next (auto).
  GpuRenderer renderer(*vk, *forest, kW, kH);
  for (Occlusion occlusion : {Occlusion::On, Occlusion::Auto}) {
    FrameSettings s = settings(ground(0.02f, 0.1f), false);
    s.occlusion = occlusion;
    const FrameResult lit = complete(renderer, s);
    s.mode = VGEO_MODE_PYRAMID;
    s.pyramidViewLevel = 1;
    const FrameResult pyramid = complete(renderer, s);
    ASSERT_EQ(pyramid.rgba.size(), lit.rgba.size());
    uint32_t deep = 0;
    for (uint32_t y = 0; y < kH; y++)
      for (uint32_t x = 0; x < kW; x++) {
        if (pyramid.rgba[4 * (y * kW + x)] < 20) continue;  // black: no depth
        deep++;
        for (uint32_t p : {(y & ~1u) * kW + (x & ~1u), (y & ~1u) * kW + (x | 1u), (y | 1u) * kW + (x & ~1u),
                           (y | 1u) * kW + (x | 1u)})
          ASSERT_TRUE(isCovered(&lit.rgba[4 * p])) << "a depth over background at " << x << ", " << y;
      }
    EXPECT_GT(deep, kW * kH / 20) << "the pyramid holds the forest's depth";
  }
}

TEST(OcclusionPolicy, KeepsTheFasterWayAndProbesTheOtherEveryPeriod) {
  OcclusionPolicy policy;
  std::vector<OcclusionPlan> plans;
  bool pyramid = false;
  for (int frame = 0; frame < 64; frame++) {
    const OcclusionPlan plan = policy.next(pyramid);
    pyramid = pyramid || plan != OcclusionPlan::OnePass;
    plans.push_back(plan);
    // One pass takes 1 ms (its pyramid 0.3 more); two passes 1.2 ms up to frame 19, then 0.5.
    const bool two = plan == OcclusionPlan::TwoPass;
    const double pyramidMs = plan == OcclusionPlan::OnePass ? 0.0 : 0.3;
    policy.record(plan, two ? (frame < 20 ? 1.2 : 0.5) : 1.0 + pyramidMs, pyramidMs);
  }
  EXPECT_EQ(plans[0], OcclusionPlan::OnePass);
  EXPECT_EQ(plans[1], OcclusionPlan::OnePass);
  EXPECT_EQ(plans[2], OcclusionPlan::OnePassThenPyramid);
  EXPECT_EQ(plans[3], OcclusionPlan::TwoPass);  // 1.2 against 1.0 (the pyramid not counted): one pass wins
  const size_t probe = 3 + kOcclusionProbePeriod + 1;
  for (size_t f = 4; f < probe - 1; f++) EXPECT_EQ(plans[f], OcclusionPlan::OnePass) << f;
  EXPECT_EQ(plans[probe - 1], OcclusionPlan::OnePassThenPyramid);
  EXPECT_EQ(plans[probe], OcclusionPlan::TwoPass);  // 0.5 now: two passes win
  // From then on two passes, and every period one frame in one pass (leaving a pyramid), which loses.
  const size_t period = kOcclusionProbePeriod + 1;
  ASSERT_LT(probe + 2 * period, plans.size());
  for (size_t f = probe + 1; f < plans.size(); f++)
    EXPECT_EQ(plans[f], (f - probe) % period == 0 ? OcclusionPlan::OnePassThenPyramid : OcclusionPlan::TwoPass) << f;
  EXPECT_TRUE(policy.twoPassWins());
  // A two-pass frame slower than the last one-pass frame goes back to one pass at once.
  policy.record(OcclusionPlan::TwoPass, 2.0, 0.0);
  EXPECT_FALSE(policy.twoPassWins());
  EXPECT_EQ(policy.next(true), OcclusionPlan::OnePass);
}

}  // namespace
}  // namespace vgeo
