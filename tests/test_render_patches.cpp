// test_render_patches.cpp: leaves drawn as tessellated limit-surface patches, on lavapipe (or any device)
// with the validation layer, each test twice: with --raster auto (on lavapipe the hardware tessellator,
// patch.tesc and patch.tese) and with --raster software (every patch it can take tessellated and
// rasterized in compute, raster_patches.comp): no crack where most leaves are patches nor at the
// transition between patch-drawn and triangle-drawn leaves, a silhouette within a pixel of the surface
// subdivided 6 levels deeper, the same shading as the triangles, the same picture either way, and the
// stats.
#include <algorithm>
#include <cmath>

#include "../renderer/gpu_renderer.h"
#include "../renderer/image.h"
#include "render_util.h"
#include "cages.h"
#include "test_util.h"

namespace vgeo {
namespace {

constexpr uint32_t kW = 256, kH = 192;

class RenderPatches : public test::GpuSuite, public ::testing::WithParamInterface<Raster> {
 protected:
  static void SetUpTestSuite() {
    openSuite("vgeo_render_patch_tests");
    // The shipped cage at --subdiv 2 (patches) and at --subdiv 5 (leaves fine enough to stand for the surface).
    writeVgeo(test::build(test::asset("horned_cube.obj"), 2), *dir + "/horned2.vgeo");
    writeVgeo(test::build(test::asset("horned_cube.obj"), 5), *dir + "/horned5.vgeo");
    horned = new RenderScene(loadRenderScene(*dir + "/horned2.vgeo"));
    hornedFine = new RenderScene(loadRenderScene(*dir + "/horned5.vgeo"));
  }
  static void TearDownTestSuite() {
    delete horned;
    delete hornedFine;
    closeSuite();
  }

  static FrameSettings settings(const RenderScene& scene, const Camera& camera, float tau, bool patches) {
    FrameSettings s = test::frameSettings(scene, camera, tau, kW, kH);
    s.patches = patches;
    s.raster = GetParam();
    return s;
  }
  // With --raster software, the compute rasterizer drew patches (not those whose micro-triangles would
  // be too large for one invocation, or that reach the near plane: the tessellator draws them).
  static void expectPatchesInCompute(const FrameResult& r) {
    if (GetParam() == Raster::Software && r.patchesDrawn > 0) {
      EXPECT_GT(r.softwarePatches, 0u) << r.patchesDrawn << " patches";
    }
  }
  // Pixels covered in `a` with no pixel of `b` within `radius` (Chebyshev distance), inside a margin.
  static int farFrom(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int radius, bool covered) {
    int count = 0;
    for (int y = radius; y < int(kH) - radius; y++)
      for (int x = radius; x < int(kW) - radius; x++) {
        if (a[size_t(y * int(kW) + x)] != covered) continue;
        bool near = false;
        for (int dy = -radius; dy <= radius && !near; dy++)
          for (int dx = -radius; dx <= radius && !near; dx++) near = b[size_t((y + dy) * int(kW) + x + dx)] == covered;
        if (!near) count++;
      }
    return count;
  }

  static RenderScene *horned, *hornedFine;
};
RenderScene* RenderPatches::horned = nullptr;
RenderScene* RenderPatches::hornedFine = nullptr;

TEST_P(RenderPatches, NoCracksCloseUpAndAtTheTransition) {
  // Background where the fine surface (subdiv 5, every leaf, no patches) covers a pixel and all its
  // neighbours within ceil(tau) + 1 would be a crack. Close views draw most leaves as patches; farther
  // ones mix patch-drawn and triangle-drawn leaves.
  GpuRenderer renderer(*vk, *horned, kW, kH), fine(*vk, *hornedFine, kW, kH);
  int closeViews = 0, transitionViews = 0;
  for (int view = 0; view < 8; view++) {
    Camera camera =
        test::orbit(*horned, 0.8f * float(view), 0.7f * std::sin(1.3f * float(view)), view % 2 ? 0.75f : 1.3f);
    std::vector<uint8_t> full = test::coverage(fine.renderFrame(settings(*hornedFine, camera, 0.0f, false)));
    for (float tau : {0.5f, 1.0f, 4.0f}) {
      FrameResult r = renderer.renderFrame(settings(*horned, camera, tau, true));
      ASSERT_TRUE(r.complete);
      expectPatchesInCompute(r);
      // With patches in compute, those left to the hardware are drawn from their grids: no depth pass.
      if (GetParam() == Raster::Software) {
        EXPECT_TRUE(r.drewIntoVisibility) << "view " << view << " tau " << tau;
      }
      const uint32_t listed = r.counters.drawCount, patched = r.counters.patchClusters;
      if (patched * 2 > listed) closeViews++;
      if (patched > 0 && patched < listed) transitionViews++;
      EXPECT_EQ(test::leaks(full, test::coverage(r), int(kW), int(kH), int(std::ceil(tau)) + 1), 0)
          << "view " << view << " tau " << tau << ": " << patched << " of " << listed << " clusters as patches";
    }
  }
  EXPECT_GE(closeViews, 4) << "views where most listed clusters are patch-drawn";
  EXPECT_GE(transitionViews, 4) << "views mixing patch-drawn and triangle-drawn leaves";
}

TEST_P(RenderPatches, ThousandsOfPatchesCoverWhatTheTrianglesCover) {
  // A close-up of CGAL's cow after one round with over 10,000 patches drawn at 1920x1080: the patches
  // are the surface the leaf triangles sample, so they cover the same pixels (within 0.1%: silhouettes
  // move by under a pixel), and the same frame twice is the same image. A patch list indexed wrongly
  // (lavapipe splits large tessellated draws into batches) drops or repeats patches past a few thousand.
  constexpr uint32_t w = 1920, h = 1080;
  const std::string tmp = test::tempDir();  // its own: the suite's two instances may run side by side
  writeVgeo(test::build(test::cgalMesh("cow.off"), 1), tmp + "/cow1.vgeo");
  RenderScene cow = loadRenderScene(tmp + "/cow1.vgeo");
  GpuRenderer renderer(*vk, cow, w, h);
  Camera camera;
  camera.eye = {0.2f, 0.2f, 0.4f};
  camera.target = {0.0f, 0.0f, 0.0f};
  FrameSettings s = test::frameSettings(cow, camera, 0.25f, w, h);
  s.patches = true;
  s.raster = GetParam();
  FrameResult with = renderer.renderFrame(s), again = renderer.renderFrame(s);
  expectPatchesInCompute(with);
  s.patches = false;
  FrameResult without = renderer.renderFrame(s);
  ASSERT_GT(with.patchesDrawn, 10000u);
  auto covered = [](const FrameResult& r) {
    std::vector<uint8_t> mask = test::coverage(r);
    return int64_t(std::count(mask.begin(), mask.end(), uint8_t(1)));
  };
  const int64_t a = covered(with), b = covered(without);
  ASSERT_GT(b, int64_t(w * h / 4));
  EXPECT_LE(std::abs(a - b), b / 1000) << a << " pixels covered with patches, " << b << " without";
  EXPECT_TRUE(with.rgba == again.rgba) << "the same frame twice gave different images";
}

TEST_P(RenderPatches, ATauFarBelowTheLeavesCostsAboutThePixels) {
  // tau = 1e-9 asks every leaf for more detail than any tessellation gives. No segment is made shorter
  // than two pixels (by an estimate that ignores foreshortening), so patches and their triangles stay a
  // few a covered pixel, front and back sides together (at factor 64 everywhere they were 8,192 a
  // patch), faces smaller than that are drawn as their leaf triangles, and the picture covers what a
  // sane tau covers: with thousands of patches at high factors, also a test of lavapipe's tessellator
  // runs (16-bit indices), which joined unrelated vertices when one run held too many patches.
  GpuRenderer renderer(*vk, *horned, kW, kH);
  for (float distance : {0.75f, 1.6f, 4.0f}) {
    Camera camera = test::orbit(*horned, 0.3f, 0.5f, distance);
    FrameResult tiny = renderer.renderFrame(settings(*horned, camera, 1e-9f, true));
    for (int i = 0; i < 4 && !tiny.complete; i++) tiny = renderer.renderFrame(settings(*horned, camera, 1e-9f, true));
    ASSERT_TRUE(tiny.complete);
    FrameResult sane = renderer.renderFrame(settings(*horned, camera, 0.5f, true));
    std::vector<uint8_t> a = test::coverage(tiny), b = test::coverage(sane);
    const int64_t covered = std::count(a.begin(), a.end(), uint8_t(1));
    ASSERT_GT(covered, 1000);
    EXPECT_LE(int64_t(tiny.patchesDrawn), covered) << "at " << distance << " radii";
    if (tiny.patchTriangles >= 0) {
      EXPECT_LE(tiny.patchTriangles, 6 * covered) << "at " << distance << " radii";
    }
    EXPECT_EQ(farFrom(a, b, 1, true), 0) << "at " << distance << " radii";
    EXPECT_EQ(farFrom(a, b, 1, false), 0) << "at " << distance << " radii";
  }
}

TEST_P(RenderPatches, ShadingMatchesTheTriangles) {
  // The same close view with and without patches: patches are the surface the leaf triangles sample,
  // with the same normals at the corners, so the lit pictures differ little (a flipped winding or normal
  // would darken every patch).
  GpuRenderer renderer(*vk, *horned, kW, kH);
  Camera camera = test::orbit(*horned, 0.9f, 0.4f, 0.75f);
  FrameResult with = renderer.renderFrame(settings(*horned, camera, 0.25f, true));
  FrameResult without = renderer.renderFrame(settings(*horned, camera, 0.25f, false));
  ASSERT_GT(with.patchesDrawn, 100u);
  expectPatchesInCompute(with);
  EXPECT_EQ(without.patchesDrawn, 0u);
  EXPECT_EQ(without.patchTriangles, 0);
  if (with.patchTriangles >= 0) {
    EXPECT_GE(with.patchTriangles, int64_t(2 * with.patchesDrawn));
  }
  double difference = 0.0;
  uint64_t both = 0;
  for (uint32_t i = 0; i < kW * kH; i++)
    if (isCovered(&with.rgba[4 * i]) && isCovered(&without.rgba[4 * i])) {
      both++;
      for (int c = 0; c < 3; c++) difference += std::abs(int(with.rgba[4 * i + c]) - int(without.rgba[4 * i + c]));
    }
  ASSERT_GT(both, kW * kH / 4);
  EXPECT_LT(difference / double(3 * both), 4.0) << "mean channel difference of the covered pixels";
  // The patch debug view colours patches (by factor) apart from triangles (grey).
  FrameSettings s = settings(*horned, camera, 0.25f, true);
  s.mode = VGEO_MODE_PATCH;
  FrameResult colours = renderer.renderFrame(s);
  uint64_t tinted = 0;
  for (uint32_t i = 0; i < kW * kH; i++) {
    const uint8_t* p = &colours.rgba[4 * i];
    if (isCovered(p) && (std::abs(int(p[0]) - int(p[2])) > 40)) tinted++;
  }
  EXPECT_GT(tinted, both / 2);
}

TEST_P(RenderPatches, SilhouetteWithinAPixelOfSixLevelsDeeper) {
  // A cube cage after one round (every face a ring around a valence-3 vertex), drawn close up with
  // patches, against the same cage after 7 rounds drawn as its leaf triangles (at limit positions).
  const std::string tmp = test::tempDir();  // its own: the suite's two instances may run side by side
  std::string cage = test::cubeCage(tmp);
  writeVgeo(test::build(cage, 1), tmp + "/cube1.vgeo");
  writeVgeo(test::build(cage, 7), tmp + "/cube7.vgeo");
  RenderScene coarse = loadRenderScene(tmp + "/cube1.vgeo"), deep = loadRenderScene(tmp + "/cube7.vgeo");
  GpuRenderer withPatches(*vk, coarse, kW, kH), reference(*vk, deep, kW, kH);
  for (int view = 0; view < 4; view++) {
    Camera camera = test::orbit(coarse, 0.5f + 1.7f * float(view), 0.35f * float(view % 3) - 0.3f, 1.35f);
    FrameResult r = withPatches.renderFrame(settings(coarse, camera, 1.0f, true));
    ASSERT_GT(r.patchesDrawn, 0u) << "view " << view;
    expectPatchesInCompute(r);
    std::vector<uint8_t> a = test::coverage(r),
                         b = test::coverage(reference.renderFrame(settings(deep, camera, 0.0f, false)));
    EXPECT_EQ(farFrom(a, b, 1, true), 0) << "view " << view
                                         << ": covered pixels more than a pixel outside the deep silhouette";
    EXPECT_EQ(farFrom(a, b, 1, false), 0) << "view " << view << ": background more than a pixel inside it";
    // Drawn as its leaf triangles instead, the same cage is visibly off: the test can fail.
    std::vector<uint8_t> flat = test::coverage(withPatches.renderFrame(settings(coarse, camera, 1.0f, false)));
    EXPECT_GT(farFrom(flat, b, 1, true) + farFrom(flat, b, 1, false), 20) << "view " << view;
  }
}

TEST_P(RenderPatches, BoundaryAndTreePatchesWithinAPixelOfSixLevelsDeeper) {
  // Open cages (boundary patches with phantom points; trees at an extraordinary boundary vertex) and a
  // triangle cage after one round (every face a tree): close up with patches against the cage 6 rounds
  // deeper. Background inside the deep silhouette would be a crack; coverage outside it a wrong surface.
  const std::string tmp = test::tempDir();
  for (const auto& [cage, levels] :
       {std::pair{test::lSheet(tmp), 1}, std::pair{test::triangleFan(tmp), 1}, std::pair{test::openBox(tmp), 1}}) {
    writeVgeo(test::build(cage, levels), tmp + "/open_coarse.vgeo");
    writeVgeo(test::build(cage, levels + 6), tmp + "/open_deep.vgeo");
    RenderScene coarse = loadRenderScene(tmp + "/open_coarse.vgeo"), deep = loadRenderScene(tmp + "/open_deep.vgeo");
    GpuRenderer withPatches(*vk, coarse, kW, kH), reference(*vk, deep, kW, kH);
    int flatMisses = 0;
    for (int view = 0; view < 3; view++) {
      Camera camera = test::orbit(coarse, 0.4f + 2.1f * float(view), 0.5f + 0.3f * float(view), 0.9f);
      FrameResult r = withPatches.renderFrame(settings(coarse, camera, 1.0f, true));
      ASSERT_TRUE(r.complete);
      EXPECT_GT(r.patchesDrawn, 0u) << cage << " view " << view;
      expectPatchesInCompute(r);
      std::vector<uint8_t> a = test::coverage(r),
                           b = test::coverage(reference.renderFrame(settings(deep, camera, 0.0f, false)));
      EXPECT_EQ(farFrom(a, b, 1, true), 0)
          << cage << " view " << view << ": covered pixels more than a pixel outside the deep surface";
      EXPECT_EQ(farFrom(a, b, 1, false), 0) << cage << " view " << view << ": background more than a pixel inside it";
      std::vector<uint8_t> flat = test::coverage(withPatches.renderFrame(settings(coarse, camera, 1.0f, false)));
      flatMisses += farFrom(flat, b, 1, true) + farFrom(flat, b, 1, false);
    }
    std::printf("%s: flat leaves %d pixels off\n", cage.c_str(), flatMisses);
    EXPECT_GT(flatMisses, 20) << cage << ": drawn as its leaf triangles the cage is visibly off (the test can fail)";
  }
}

TEST_P(RenderPatches, ComputeMatchesTheTessellator) {
  // Close views drawn with the patches in compute and through the tessellator: the same edge points
  // (patch_surface.glsl) and the same surface, triangulated differently inside a face, so the covered
  // pixels agree but for silhouette pixels (none more than a pixel from the other's) and the shading
  // barely differs (normals interpolated over other triangles).
  if (GetParam() != Raster::Software) GTEST_SKIP() << "compares the two paths once";
  GpuRenderer renderer(*vk, *horned, kW, kH);
  uint32_t compared = 0;
  for (int view = 0; view < 3; view++) {
    Camera camera =
        test::orbit(*horned, 0.9f + 2.0f * float(view), 0.4f - 0.3f * float(view), 0.7f + 0.3f * float(view));
    FrameSettings s = settings(*horned, camera, 0.5f, true);
    FrameResult compute = renderer.renderFrame(s);
    s.raster = Raster::Hardware;
    FrameResult tessellated = renderer.renderFrame(s);
    ASSERT_GT(compute.softwarePatches, 0u) << "view " << view;
    compared += compute.softwarePatches;
    EXPECT_EQ(tessellated.softwarePatches, 0u);
    EXPECT_EQ(compute.patchesDrawn, tessellated.patchesDrawn) << "view " << view;
    std::vector<uint8_t> a = test::coverage(compute), b = test::coverage(tessellated);
    EXPECT_EQ(farFrom(a, b, 1, true), 0) << "view " << view;
    EXPECT_EQ(farFrom(a, b, 1, false), 0) << "view " << view;
    uint64_t both = 0, apart = 0;
    for (uint32_t i = 0; i < kW * kH; i++)
      if (a[i] && b[i]) {
        both++;
        int most = 0;
        for (int c = 0; c < 3; c++)
          most = std::max(most, std::abs(int(compute.rgba[4 * i + c]) - int(tessellated.rgba[4 * i + c])));
        if (most > 8) apart++;
      }
    ASSERT_GT(both, kW * kH / 8) << "view " << view;
    EXPECT_LE(apart * 100, both) << "view " << view << ": pixels whose colour differs by more than 8 of 255";
  }
  // Enough patches over the three views that the comparison means something (the farthest view's cut
  // may hold few leaves, as many as the DAG's group errors leave there).
  EXPECT_GT(compared, 500u);
}

INSTANTIATE_TEST_SUITE_P(Rasters, RenderPatches, ::testing::Values(Raster::Auto, Raster::Software),
                         [](const ::testing::TestParamInfo<Raster>& info) {
                           return info.param == Raster::Software ? "Compute" : "Auto";
                         });

}  // namespace
}  // namespace vgeo
