// test_render_large_scenes.cpp: scenes whose arrays pass what one storage-buffer binding may hold
// (maxStorageBufferRange, 128 MiB on lavapipe), on lavapipe (or any device) with the validation layer:
// the renderer reads the scene's arrays by device address, so they render, and render the same as the
// scene would if it were small.
#include <algorithm>

#include "../common/vgeo_file.h"
#include "../renderer/gpu_renderer.h"
#include "render_util.h"
#include "test_util.h"

namespace vgeo {
namespace {

constexpr uint32_t kW = 256, kH = 192;
constexpr size_t kBindingLimit = size_t(128) << 20;  // lavapipe's maxStorageBufferRange

class RenderLargeScenes : public test::GpuSuite {
 protected:
  static void SetUpTestSuite() { openSuite("vgeo_render_large_scene_tests"); }
  static void TearDownTestSuite() { closeSuite(); }

  // A complete frame whose draw list equals the CPU reference cut.
  static FrameResult renderAndCompare(GpuRenderer& renderer, const RenderScene& scene, const FrameSettings& s) {
    return test::renderEqualToCut(renderer, s, selectSceneCut(scene, s.cullView, s.tau));
  }
};

TEST_F(RenderLargeScenes, GeometryPastTheFirst128MiBOfItsArrays) {
  // The shipped cage's vertices moved behind 11.5 M unused ones: its positions start 132 MiB into their
  // array. The picture and the cut are those of the scene as it was.
  writeVgeo(test::build(test::asset("horned_cube.obj"), 3), *dir + "/horned.vgeo");
  RenderScene small = loadRenderScene(*dir + "/horned.vgeo");
  RenderScene large = small;
  const uint32_t unused = 11'500'000;
  VgeoData& d = large.data;
  d.positions.insert(d.positions.begin(), size_t(3) * unused, 0.0f);
  d.normals.insert(d.normals.begin(), unused, 0u);
  for (uint32_t& v : d.clusterVertices) v += unused;
  for (uint32_t& v : d.cageFaceVertices) v += unused;
  for (auto& g : d.geometries) g.vertexOffset += unused;
  ASSERT_GT(d.positions.size() * sizeof(float), kBindingLimit);
  GpuRenderer smallRenderer(*vk, small, kW, kH), largeRenderer(*vk, large, kW, kH);
  EXPECT_FALSE(smallRenderer.readsSceneByAddress());
  EXPECT_TRUE(largeRenderer.readsSceneByAddress());
  for (int view = 0; view < 3; view++) {
    Camera camera = test::orbit(small, 0.7f + 2.0f * float(view), 0.3f, 1.2f + float(view));
    for (uint32_t mode : {VGEO_MODE_LIT, VGEO_MODE_TRIANGLE}) {
      FrameSettings s = test::frameSettings(small, camera, 1.0f, kW, kH);
      s.mode = mode;
      s.patches = false;  // patch records name control points by index: not moved here
      FrameResult want = renderAndCompare(smallRenderer, small, s);
      FrameResult got = renderAndCompare(largeRenderer, large, s);
      EXPECT_GT(got.trianglesDrawn, 0u);
      EXPECT_EQ(got.trianglesDrawn, want.trianglesDrawn) << "view " << view;
      EXPECT_TRUE(got.rgba == want.rgba) << "view " << view << " mode " << mode;
    }
  }
}

TEST_F(RenderLargeScenes, ArraysByAddressDrawWhatBindingsDraw) {
  // The shaders' two variants (common.glsl) on one small scene, patches and every view: the same pixels.
  writeVgeo(test::build(test::asset("horned_cube.obj"), 2), *dir + "/horned2.vgeo");
  RenderScene scene = loadRenderScene(*dir + "/horned2.vgeo");
  GpuRenderer bindings(*vk, scene, kW, kH), addresses(*vk, scene, kW, kH, true);
  EXPECT_FALSE(bindings.readsSceneByAddress());
  EXPECT_TRUE(addresses.readsSceneByAddress());
  for (int view = 0; view < 2; view++) {
    Camera camera = test::orbit(scene, 0.4f + 2.0f * float(view), 0.4f, view == 0 ? 0.5f : 2.0f);
    for (uint32_t mode = VGEO_MODE_LIT; mode <= VGEO_MODE_PATCH; mode++) {
      FrameSettings s = test::frameSettings(scene, camera, 0.5f, kW, kH);
      s.mode = mode;
      FrameResult want = renderAndCompare(bindings, scene, s), got = renderAndCompare(addresses, scene, s);
      if (view == 0 && mode == VGEO_MODE_LIT) {
        EXPECT_GT(want.patchesDrawn, 0u);
      }
      EXPECT_EQ(got.patchesDrawn, want.patchesDrawn);
      EXPECT_TRUE(got.rgba == want.rgba) << "view " << view << " mode " << mode;
    }
  }
}

TEST_F(RenderLargeScenes, ArmadilloSubdividedThreeTimes) {
  // 5 M leaf triangles, 2.5 M patches, whose control-point indices pass 128 MiB. Close views draw patches.
  writeVgeo(test::build(test::cgalMesh("armadillo.off"), 3), *dir + "/armadillo3.vgeo");
  RenderScene scene = loadRenderScene(*dir + "/armadillo3.vgeo");
  ASSERT_GT(scene.data.patchPoints.size() * sizeof(uint32_t), kBindingLimit);
  GpuRenderer renderer(*vk, scene, kW, kH);
  EXPECT_TRUE(renderer.readsSceneByAddress());
  for (float distance : {1.5f, 0.3f}) {
    const float tau = distance < 1.0f ? 0.02f : 1.0f;  // the leaves are within 0.1 px of the surface here
    FrameSettings s = test::frameSettings(scene, test::orbit(scene, 0.5f, 0.2f, distance), tau, kW, kH);
    FrameResult r = renderAndCompare(renderer, scene, s);
    size_t covered = 0;
    for (uint8_t m : test::coverage(r)) covered += m;
    EXPECT_GT(covered, size_t(kW * kH / 20)) << "distance " << distance;
    if (distance < 1.0f) {
      EXPECT_GT(r.patchesDrawn, 0u);
    }
  }
}

}  // namespace
}  // namespace vgeo
