// test_render_occlusion.cpp: two-pass occlusion culling on lavapipe (or any device) with the validation
// layer, on a dense forest of the shipped cage: along a camera path that moves, turns and jumps, the
// picture with occlusion culling equals the picture without, frame by frame; what it draws is a subset of
// the CPU reference cut and holds every cluster the picture shows; it does hide things from the ground;
// and a frozen cut keeps its occlusion while the camera moves.
#include <algorithm>

#include "../common/vgeo_file.h"
#include "../renderer/gpu_renderer.h"
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
    s.occlusion = occlusion;
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

}  // namespace
}  // namespace vgeo
