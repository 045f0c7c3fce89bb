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
          EXPECT_TRUE(b.bareRenderPass);
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
    ASSERT_TRUE(b.bareRenderPass);
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

TEST_F(RenderOcclusion, AutoRunsTwoPassesWhileTheyHideATenth) {
  // From the ground two passes hide most of the forest: Auto runs them from its first probe on. Above it,
  // where they hide less than a tenth of what is drawn, it goes back to one pass and probes again (a
  // frame that leaves a pyramid, then a two-pass frame). Every picture is the one without.
  GpuRenderer automatic(*vk, *forest, kW, kH), plain(*vk, *forest, kW, kH);
  std::vector<Camera> path;
  for (int i = 0; i < 8; i++) path.push_back(ground(0.01f * float(i), 0.02f * float(i)));
  for (int i = 0; i < 2 * int(kOcclusionProbePeriod) + 6; i++) path.push_back(above());
  for (const Camera& camera : path) complete(automatic, settings(camera, false));  // lists grown, no policy step
  uint32_t twoPass = 0, probesAbove = 0, onePassAbove = 0;
  bool paid = false;       // what the last two-pass frame said of itself
  bool probeNext = false;  // the last frame ran one pass and left a pyramid
  for (size_t i = 0; i < path.size(); i++) {
    FrameSettings s = settings(path[i], false), without = s;
    s.occlusion = Occlusion::Auto;
    const FrameResult a = automatic.renderFrame(s), b = complete(plain, without);
    ASSERT_TRUE(a.complete) << "frame " << i;
    EXPECT_TRUE(a.rgba == b.rgba) << "frame " << i;
    if (i < 3) {  // two one-pass frames, then one leaves a pyramid
      EXPECT_FALSE(a.occlusion) << "frame " << i;
    }
    if (i < 8) {
      EXPECT_EQ(a.pyramidBuilt, a.occlusion || i == 2) << "frame " << i;
    }
    if (probeNext) {
      EXPECT_TRUE(a.occlusion) << "frame " << i << ": no probe after the pyramid";
    }
    probeNext = a.pyramidBuilt && !a.occlusion;
    if (paid && i < 8) {
      EXPECT_TRUE(a.occlusion) << "frame " << i << ": two passes that hid plenty were dropped";
    }
    if (a.occlusion) {
      twoPass++;
      const auto& c = a.counters;
      const uint64_t perInstance = std::max<uint64_t>(c.drawCount / std::max(c.visibleInstances, 1u), 1);
      const uint64_t hidden = c.occludedClusters + (uint64_t(c.occludedInstances) + c.occludedNodes) * perInstance;
      paid = hidden > 0 && hidden * kOcclusionPaysAbove >= c.drawCount;
      if (i < 8) {
        EXPECT_TRUE(paid) << "frame " << i << ": from the ground two passes hide a tenth";
      }
      if (i >= 8) probesAbove += !paid;
    } else if (i >= 8) {
      onePassAbove++;
    }
  }
  EXPECT_GE(twoPass, 5u);
  EXPECT_GE(probesAbove, 2u);  // the first frame above, and one probe at least
  EXPECT_GE(onePassAbove, kOcclusionProbePeriod);
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

TEST(OcclusionPolicy, ProbesEveryPeriodWhileTwoPassesDoNotPay) {
  OcclusionPolicy policy;
  std::vector<OcclusionPlan> plans;
  bool pyramid = false;
  for (int frame = 0; frame < 40; frame++) {
    const OcclusionPlan plan = policy.next(pyramid);
    pyramid = pyramid || plan != OcclusionPlan::OnePass;
    plans.push_back(plan);
    // Frames 0-19 hide nothing, 20 on half of what they draw.
    policy.record(plan, 0, frame < 20 ? 0 : 500, 1000, 100);
  }
  EXPECT_EQ(plans[0], OcclusionPlan::OnePass);
  EXPECT_EQ(plans[1], OcclusionPlan::OnePass);
  EXPECT_EQ(plans[2], OcclusionPlan::OnePassThenPyramid);
  EXPECT_EQ(plans[3], OcclusionPlan::TwoPass);
  const size_t next = 3 + kOcclusionProbePeriod + 1;  // the next probe, and the frame before it
  for (size_t f = 4; f < next - 1; f++) EXPECT_EQ(plans[f], OcclusionPlan::OnePass) << f;
  EXPECT_EQ(plans[next - 1], OcclusionPlan::OnePassThenPyramid);
  EXPECT_EQ(plans[next], OcclusionPlan::TwoPass);
  // The probe after frame 20 finds that two passes pay, and every frame after it runs them.
  const size_t paying = next + kOcclusionProbePeriod + 1;
  ASSERT_GT(paying, size_t(20));
  for (size_t f = paying; f < plans.size(); f++) EXPECT_EQ(plans[f], OcclusionPlan::TwoPass) << f;
  // A frame that hides an instance hides what an instance draws on average: 1 of 100 instances, each
  // drawing 10 of the 1,000 clusters, is a hundredth, under a tenth; 10 of them pay.
  OcclusionPolicy one, ten;
  one.record(OcclusionPlan::TwoPass, 1, 0, 1000, 100);
  ten.record(OcclusionPlan::TwoPass, 10, 0, 1000, 100);
  EXPECT_FALSE(one.pays());
  EXPECT_TRUE(ten.pays());
}

}  // namespace
}  // namespace vgeo
