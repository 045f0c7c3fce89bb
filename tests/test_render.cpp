// test_render.cpp: the GPU renderer on lavapipe (or any device), with the Khronos validation layer and
// synchronization validation on: every test fails on any validation message.
#include <cmath>

#include "../renderer/gpu_renderer.h"
#include "../renderer/image.h"
#include "render_util.h"
#include "test_util.h"

namespace vgeo {
namespace {

constexpr uint32_t kW = 256, kH = 192;

// One Vulkan device (with validation) for the whole suite, and the scenes it draws.
class Render : public test::GpuSuite {
 protected:
  static void SetUpTestSuite() {
    openSuite("vgeo_render_tests");
    writeVgeo(test::build(test::asset("horned_cube.obj"), 3), *dir + "/horned.vgeo");
    writeVgeo(test::build(test::cgalMesh("armadillo.off"), 0), *dir + "/armadillo.vgeo");
    writeVgeo(test::build(test::cgalMesh("lion.off"), 0), *dir + "/lion.vgeo");
    single = new RenderScene(loadRenderScene(*dir + "/horned.vgeo"));
    grid = new RenderScene(loadRenderScene(*dir + "/horned.vgeo", 4));
    armadillo = new RenderScene(loadRenderScene(*dir + "/armadillo.vgeo"));
    openLion = new RenderScene(loadRenderScene(*dir + "/lion.vgeo"));
  }
  static void TearDownTestSuite() {
    delete single;
    delete grid;
    delete armadillo;
    delete openLion;
    closeSuite();
  }

  static FrameSettings settingsFor(const RenderScene& scene, const Camera& camera, float tau,
                                   Traversal t = Traversal::Persistent, uint32_t width = kW, uint32_t height = kH) {
    FrameSettings s = test::frameSettings(scene, camera, tau, width, height);
    s.traversal = t;
    return s;
  }

  static RenderScene *single, *grid, *armadillo, *openLion;  // openLion: an open surface (CGAL's lion.off)
};
RenderScene* Render::single = nullptr;
RenderScene* Render::grid = nullptr;
RenderScene* Render::armadillo = nullptr;
RenderScene* Render::openLion = nullptr;

TEST_F(Render, GpuDrawListEqualsCpuCutForAllTraversals) {
  for (const RenderScene* scene : {single, grid}) {
    GpuRenderer renderer(*vk, *scene, kW, kH);
    glm::vec3 c(scene->bounds);
    float r = scene->bounds.w;
    std::vector<Camera> cameras = {defaultCamera(scene->bounds, scene->boxMin, scene->boxMax, 60.0f),
                                   test::orbit(*scene, 0.7f, 0.4f, 1.4f), test::orbit(*scene, 2.5f, -0.3f, 6.0f)};
    Camera inside;  // inside the scene, looking along it
    inside.eye = c + glm::vec3(0.1f, 0.05f, 0.2f) * r;
    inside.target = c + glm::vec3(1.0f, 0.0f, 0.3f) * r;
    cameras.push_back(inside);
    Camera away;  // outside, looking away from it
    away.eye = c + glm::vec3(0.0f, 0.0f, 2.0f) * r;
    away.target = c + glm::vec3(0.0f, 0.0f, 4.0f) * r;
    cameras.push_back(away);
    for (Traversal t : {Traversal::Persistent, Traversal::Levels, Traversal::Flat})
      for (size_t k = 0; k < cameras.size(); k++)
        for (float tau : {0.5f, 1.0f, 4.0f, 16.0f}) {
          // Instance culling with one lane and with VGEO_CULL_INSTANCE_LANES lanes an instance, alternately.
          const uint32_t lanes = (k + uint32_t(tau)) % 2 == 0 ? 1u : uint32_t(VGEO_CULL_INSTANCE_LANES);
          SCOPED_TRACE(std::string(traversalName(t)) + " camera " + std::to_string(k) + " tau " + std::to_string(tau) +
                       (scene == grid ? " grid" : " single") + " culling lanes " + std::to_string(lanes));
          FrameSettings s = settingsFor(*scene, cameras[k], tau, t);
          s.cullLanes = lanes;
          s.readImage = false;
          FrameResult result;
          ASSERT_NO_THROW(result = renderer.renderFrame(s));
          ASSERT_TRUE(result.complete);
          SceneCut reference = selectSceneCut(*scene, s.cullView, tau);
          std::string difference;
          EXPECT_TRUE(compareCuts(reference, result.drawList, difference))
              << traversalName(t) << " camera " << k << " tau " << tau << ": " << difference;
          EXPECT_LE(reference.borderline.size(), std::max<size_t>(1, reference.entries.size() / 1000))
              << "borderline clusters over 0.1% of the visible ones";
          if (k == 4) {
            EXPECT_EQ(result.counters.drawCount, 0u) << "looking away draws nothing";
          }
        }
  }
}

TEST_F(Render, SweptLevelsGiveTheSameCutWhateverTheBudget) {
  // Sweeps (persistent traversal, spread instance culling): a whole simplification level of an instance
  // tested as runs of clusters instead of walked. No budget, one that covers every candidate, and one that
  // covers some of the culling workgroups' claims but not all: the same cut each time.
  GpuRenderer renderer(*vk, *grid, kW, kH);
  const float r = grid->bounds.w;
  Camera inside;
  inside.eye = glm::vec3(grid->bounds) + glm::vec3(0.1f, 0.05f, 0.2f) * r;
  inside.target = glm::vec3(grid->bounds) + glm::vec3(1.0f, 0.0f, 0.3f) * r;
  for (const Camera& camera :
       {defaultCamera(grid->bounds, grid->boxMin, grid->boxMax, 60.0f), test::orbit(*grid, 0.7f, 0.4f, 1.4f), inside})
    for (float tau : {1.0f, 4.0f}) {
      FrameSettings s = settingsFor(*grid, camera, tau);
      s.cullLanes = VGEO_CULL_INSTANCE_LANES;
      s.readImage = false;
      const SceneCut reference = selectSceneCut(*grid, s.cullView, tau);
      auto run = [&](uint32_t budget) {
        SCOPED_TRACE("sweep budget " + std::to_string(budget) + " tau " + std::to_string(tau));
        s.sweepBudget = budget;
        return test::renderEqualToCut(renderer, s, reference).counters;
      };
      EXPECT_EQ(run(0).sweptTests, 0u);
      const shaderio::Counters all = run(UINT32_MAX);
      ASSERT_GT(all.sweepTests, 0u) << "no level to sweep";
      EXPECT_EQ(all.sweptTests, all.sweepTests);
      // Several culling workgroups each claim their candidates: one budget test short of them
      // all, at least one claim fails; the first claim that fits is swept.
      const shaderio::Counters some = run(all.sweepTests - 1);
      EXPECT_LT(some.sweptTests, all.sweepTests);
      EXPECT_EQ(some.sweepTests, all.sweepTests);
    }
}

TEST_F(Render, CullingInsideTheTraversalGivesTheSameCut) {
  // The persistent workers cull the instances themselves (on GPUs in scenes of up to 3 instances a
  // worker), each instance counted in nodesPending until its items are queued. The CPU's cut with every
  // sweep budget (none, all, all but one test: some items walked), nodesPending back at 0, and the
  // instances counted as the culling pass counts them: with a worker for each instance and with 3 workers
  // for 16 instances. On lavapipe the workers run a few at a time, so one waiting on a later culling worker
  // leaves on its iteration budget (made small here) and a later one carries on.
  for (auto [sceneOf, fewWorkers] : {std::pair(single, false), std::pair(grid, false), std::pair(grid, true)}) {
    const RenderScene* scene =
        sceneOf;  // a plain variable: lambdas below capture it (C++20 lambdas may not capture bindings in clang 14)
    GpuRenderer renderer(*vk, *scene, kW, kH);
    renderer.setPersistentWorkgroups(fewWorkers ? 3 : uint32_t(scene->data.instances.size()) + 3);
    renderer.setIterationBudget(2000);
    FrameSettings probe = settingsFor(*scene, test::orbit(*scene, 0.7f, 0.4f, 1.4f), 1.0f);
    EXPECT_EQ(renderer.cullsInTraversal(probe), !vk->isLavapipe() && !fewWorkers)
        << "auto: on GPUs, up to 3 instances a worker";
    probe.instanceCulling = InstanceCulling::InTraversal;
    ASSERT_TRUE(renderer.cullsInTraversal(probe));
    probe.cullLanes = 1;
    EXPECT_FALSE(renderer.cullsInTraversal(probe)) << "one culling lane an instance: a pass of its own";
    probe.cullLanes = 0;
    probe.traversal = Traversal::Flat;
    EXPECT_FALSE(renderer.cullsInTraversal(probe)) << "the persistent traversal only";
    const float r = scene->bounds.w;
    Camera away;
    away.eye = glm::vec3(scene->bounds) + glm::vec3(0.0f, 0.0f, 2.0f) * r;
    away.target = glm::vec3(scene->bounds) + glm::vec3(0.0f, 0.0f, 4.0f) * r;
    for (const Camera& camera : {defaultCamera(scene->bounds, scene->boxMin, scene->boxMax, 60.0f),
                                 test::orbit(*scene, 0.7f, 0.4f, 1.4f), away})
      for (float tau : {1.0f, 4.0f}) {
        FrameSettings s = settingsFor(*scene, camera, tau);
        s.readImage = false;
        const SceneCut reference = selectSceneCut(*scene, s.cullView, tau);
        s.instanceCulling = InstanceCulling::Pass;
        const FrameResult pass = renderer.renderFrame(s);
        ASSERT_TRUE(pass.complete);
        EXPECT_FALSE(pass.culledInTraversal);
        s.instanceCulling = InstanceCulling::InTraversal;
        auto run = [&](uint32_t budget) {
          SCOPED_TRACE(std::string(scene == grid ? "grid" : "single") + " workers " +
                       std::to_string(renderer.persistentWorkgroups()) + " sweep budget " + std::to_string(budget) +
                       " tau " + std::to_string(tau));
          s.sweepBudget = budget;
          const FrameResult result = test::renderEqualToCut(renderer, s, reference);
          EXPECT_TRUE(result.culledInTraversal);
          EXPECT_EQ(result.counters.nodesPending, 0u);
          EXPECT_EQ(result.counters.visibleInstances, pass.counters.visibleInstances);
          return result.counters;
        };
        run(0);
        const shaderio::Counters all = run(UINT32_MAX);
        if (all.sweepTests > 0) {
          EXPECT_LT(run(all.sweepTests - 1).sweptTests, all.sweepTests);
        }
      }
  }
  // Forced, up to kCullInTraversalMaxPerWorker (64) instances a worker.
  const RenderScene many =
      loadRenderScene(std::filesystem::temp_directory_path() / "vgeo_render_tests" / "horned.vgeo", 9);
  GpuRenderer manyRenderer(*vk, many, kW, kH);
  FrameSettings manyProbe = settingsFor(many, test::orbit(many, 0.7f, 0.4f, 1.4f), 1.0f);
  manyProbe.instanceCulling = InstanceCulling::InTraversal;
  manyRenderer.setPersistentWorkgroups(1);
  EXPECT_FALSE(manyRenderer.cullsInTraversal(manyProbe)) << "81 instances, 1 worker";
  manyRenderer.setPersistentWorkgroups(2);
  EXPECT_TRUE(manyRenderer.cullsInTraversal(manyProbe)) << "81 instances, 2 workers";
}

TEST_F(Render, WorkerProfileAccountsForEveryItem) {
  // The profiled persistent traversal (a pipeline of its own) lists the same cut, and its records hold
  // every queue item once, in stamps that follow each other (begin <= start <= claimed <= taken <= end <=
  // exit), so that the benchmark's summary of them can be trusted.
  GpuRenderer renderer(*vk, *grid, kW, kH);
  if (!renderer.canProfileWorkers()) GTEST_SKIP() << "no shader device clock on " << vk->deviceName();
  const uint32_t workgroups = renderer.persistentWorkgroups();
  for (float tau : {1.0f, 4.0f}) {
    FrameSettings s = settingsFor(*grid, test::orbit(*grid, 0.7f, 0.4f, 1.4f), tau, Traversal::Persistent);
    s.readImage = false;
    s.profileWorkers = true;
    FrameResult result = renderer.renderFrame(s);
    ASSERT_TRUE(result.complete);
    std::string difference;
    EXPECT_TRUE(compareCuts(selectSceneCut(*grid, s.cullView, tau), result.drawList, difference)) << difference;
    ASSERT_EQ(result.workerProfile.size(), size_t(workgroups) * VGEO_PROFILE_WORKER_WORDS);
    auto at = [&](size_t w) { return uint64_t(result.workerProfile[w]) | uint64_t(result.workerProfile[w + 1]) << 32; };
    uint64_t items = 0;
    for (uint32_t g = 0; g < workgroups; g++) {
      const size_t base = size_t(g) * VGEO_PROFILE_WORKER_WORDS;
      const uint32_t recorded = result.workerProfile[base], iterations = result.workerProfile[base + 1],
                     polls = result.workerProfile[base + 2];
      ASSERT_EQ(recorded, iterations - polls) << "workgroup " << g << " took items in more iterations than it recorded";
      uint64_t last = at(base + 4);
      for (uint32_t i = 0; i < recorded; i++) {
        const size_t r = base + VGEO_PROFILE_HEADER_WORDS + size_t(i) * VGEO_PROFILE_ITERATION_WORDS;
        for (size_t stamp = r; stamp < r + 8; stamp += 2) {
          EXPECT_LE(last, at(stamp)) << "workgroup " << g << " iteration " << i;
          last = at(stamp);
        }
        EXPECT_GT(result.workerProfile[r + 8], 0u);
        items += result.workerProfile[r + 8];
      }
      EXPECT_LE(last, at(base + 6)) << "workgroup " << g << " exit";
    }
    EXPECT_EQ(items, result.counters.itemsDone) << "tau " << tau;
    EXPECT_GT(items, 0u);
  }
}

TEST_F(Render, WorkersThatRunOutOfBudgetAreDoubled) {
  // lavapipe's workers leave after an iteration budget (docs/gpu-notes.md, 1). When all of them left before the
  // queue drained, the frame is reported incomplete (no exception), and the next frames run twice as
  // many workers on a fresh queue until one drains it: the same cut as the CPU's.
  if (!vk->isLavapipe()) GTEST_SKIP() << "the iteration budget applies on lavapipe only";
  GpuRenderer renderer(*vk, *grid, kW, kH);
  renderer.setPersistentWorkgroups(1);
  renderer.setIterationBudget(1);  // one iteration a worker (up to 64 items)
  FrameSettings s = settingsFor(*grid, test::orbit(*grid, 0.7f, 0.4f, 1.4f), 1.0f, Traversal::Persistent);
  s.readImage = false;
  FrameResult first = renderer.renderFrame(s);
  EXPECT_TRUE(first.workersRanOut);
  EXPECT_FALSE(first.complete);
  EXPECT_EQ(renderer.persistentWorkgroups(), 2u);
  FrameResult next = first;
  for (int i = 0; i < 16 && !next.complete; i++) next = renderer.renderFrame(s);
  ASSERT_TRUE(next.complete);
  EXPECT_GE(renderer.persistentWorkgroups(), 2u);
  std::string difference;
  EXPECT_TRUE(compareCuts(selectSceneCut(*grid, s.cullView, 1.0f), next.drawList, difference)) << difference;
}

TEST_F(Render, LargeSceneDrawListEqualsCpuCut) {
  // Past VGEO_CULL_SPREAD_INSTANCES instances the renderer culls with one lane an instance, and on lavapipe
  // always; both lane counts give the same cut in a scene of many instances too.
  const uint32_t side = 65;
  ASSERT_GT(side * side, uint32_t(VGEO_CULL_SPREAD_INSTANCES));
  std::string dir = std::filesystem::temp_directory_path() / "vgeo_render_tests";
  RenderScene large = loadRenderScene(dir + "/horned.vgeo", side);
  GpuRenderer renderer(*vk, large, kW, kH);
  glm::vec3 c(large.bounds);
  Camera inside;
  inside.eye = c + glm::vec3(0.1f, 0.05f, 0.2f) * large.bounds.w;
  inside.target = c + glm::vec3(1.0f, 0.0f, 0.3f) * large.bounds.w;
  for (const Camera& camera : {defaultCamera(large.bounds, large.boxMin, large.boxMax, 60.0f), inside})
    for (Traversal t : {Traversal::Persistent, Traversal::Levels})
      for (float tau : {1.0f, 4.0f}) {
        const uint32_t lanes = t == Traversal::Persistent ? uint32_t(VGEO_CULL_INSTANCE_LANES) : 1u;
        SCOPED_TRACE(std::string(traversalName(t)) + " tau " + std::to_string(tau) + " culling lanes " +
                     std::to_string(lanes));
        FrameSettings s = settingsFor(large, camera, tau, t);
        s.cullLanes = lanes;
        s.readImage = false;
        FrameResult result = renderer.renderFrame(s);
        while (!result.complete) result = renderer.renderFrame(s);
        std::string difference;
        EXPECT_TRUE(compareCuts(selectSceneCut(large, s.cullView, tau), result.drawList, difference)) << difference;
        EXPECT_GT(result.drawList.size(), 0u);
      }
}

TEST_F(Render, NoCracksAtTau1And8) {
  // Background inside the silhouette of the full-detail render (tau 0: every leaf, as its triangles)
  // would be a crack. The picture may shrink by up to tau pixels at the silhouette (that much error is
  // allowed), so the full-detail mask is eroded by ceil(tau) + 1 pixels first. An open surface's outline
  // is simplified too, within its error: it may not grow past the full-detail mask dilated as much
  // either. (Patches at the leaves: test_render_patches.cpp.)
  auto background = [](std::vector<uint8_t> mask) {
    for (uint8_t& m : mask) m = !m;
    return mask;
  };
  for (const RenderScene* scene : {single, armadillo, openLion}) {
    GpuRenderer renderer(*vk, *scene, kW, kH);
    for (int view = 0; view < 6; view++) {
      Camera camera = test::orbit(*scene, 1.1f * float(view), 0.9f * std::sin(float(view)), view % 2 ? 1.6f : 2.6f);
      FrameSettings leaves = settingsFor(*scene, camera, 0.0f);
      leaves.patches = false;
      std::vector<uint8_t> full = test::coverage(renderer.renderFrame(leaves));
      for (float tau : {1.0f, 8.0f}) {
        std::vector<uint8_t> lod = test::coverage(renderer.renderFrame(settingsFor(*scene, camera, tau)));
        EXPECT_EQ(test::leaks(full, lod, int(kW), int(kH), int(std::ceil(tau)) + 1), 0)
            << "view " << view << " tau " << tau;
        EXPECT_EQ(test::leaks(background(full), background(lod), int(kW), int(kH), int(std::ceil(tau)) + 1), 0)
            << "view " << view << " tau " << tau << ": covered pixels beyond the full-detail outline";
      }
    }
  }
}

TEST_F(Render, FidelityAtTau1AndTrianglesFallWithDistance) {
  // A pixel differs when any channel differs by more than 32/255; at tau = 1 at most 0.5% may, at
  // 512x384 with the armadillo filling a third of the height.
  const uint32_t w = 512, h = 384;
  GpuRenderer renderer(*vk, *armadillo, w, h);
  Camera camera = test::orbit(*armadillo, 0.5f, 0.3f, 2.2f);
  FrameResult full = renderer.renderFrame(settingsFor(*armadillo, camera, 0.0f, Traversal::Persistent, w, h));
  FrameResult lod = renderer.renderFrame(settingsFor(*armadillo, camera, 1.0f, Traversal::Persistent, w, h));
  size_t differ = 0;
  for (size_t i = 0; i < size_t(w) * h; i++)
    for (int ch = 0; ch < 3; ch++)
      if (std::abs(int(full.rgba[4 * i + ch]) - int(lod.rgba[4 * i + ch])) > 32) {
        differ++;
        break;
      }
  EXPECT_LE(double(differ), 0.005 * w * h) << differ << " pixels differ";
  EXPECT_LT(lod.counters.triangles, full.counters.triangles);
  uint32_t previous = UINT32_MAX;
  for (float distance : {1.5f, 3.0f, 6.0f, 12.0f, 24.0f}) {
    FrameResult r = renderer.renderFrame(settingsFor(*armadillo, test::orbit(*armadillo, 0.5f, 0.3f, distance), 1.0f));
    EXPECT_LT(r.counters.triangles, previous) << "at " << distance << " radii";
    previous = r.counters.triangles;
  }
}

TEST_F(Render, OverflowIsReportedAndTheNextFrameIsComplete) {
  FrameSettings s = settingsFor(*grid, test::orbit(*grid, 0.3f, 0.5f, 1.2f), 1.0f);
  for (bool tinyQueue : {true, false}) {
    GpuRenderer renderer(*vk, *grid, kW, kH);
    renderer.setCapacities(tinyQueue ? 4 : 1u << 16, tinyQueue ? 1u << 16 : 8, 1u << 20, 1u << 16);
    FrameResult first = renderer.renderFrame(s);
    EXPECT_FALSE(first.complete);
    if (tinyQueue) {
      EXPECT_GT(first.counters.queueOverflow, 0u);
      EXPECT_GT(renderer.queueCapacity(), 4u);
    } else {
      EXPECT_GT(first.counters.drawOverflow, 0u);
      EXPECT_GT(renderer.drawCapacity(), 8u);
    }
    FrameResult next = renderer.renderFrame(s);
    for (int i = 0; i < 4 && !next.complete; i++) next = renderer.renderFrame(s);
    EXPECT_TRUE(next.complete);
    std::string difference;
    EXPECT_TRUE(compareCuts(selectSceneCut(*grid, s.cullView, 1.0f), next.drawList, difference)) << difference;
  }
}

TEST_F(Render, AFrameMemoryLimitStopsGrowthWithAClearError) {
  // Lists that overflow grow for the next frame, but never past the frame memory limit: a cut that
  // needs more stops with FrameMemoryError naming the need, the limit and the way out.
  GpuRenderer renderer(*vk, *grid, kW, kH);
  renderer.setCapacities(16, 16, 64, 16);
  renderer.setFrameMemoryLimit(4096);
  FrameSettings s = settingsFor(*grid, test::orbit(*grid, 0.5f, 0.4f, 1.2f), 1.0f);
  try {
    for (int i = 0; i < 4; i++) renderer.renderFrame(s);
    FAIL() << "no error";
  } catch (const FrameMemoryError& e) {
    EXPECT_NE(std::string(e.what()).find("past the limit of"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--max-frame-memory"), std::string::npos) << e.what();
  }
  // With room, the same frame completes after growing.
  renderer.setFrameMemoryLimit(uint64_t(kDefaultFrameMemoryMiB) << 20);
  FrameResult r = renderer.renderFrame(s);
  for (int i = 0; i < 8 && !r.complete; i++) r = renderer.renderFrame(s);
  EXPECT_TRUE(r.complete);
}

TEST_F(Render, EveryDebugModeRenders) {
  GpuRenderer renderer(*vk, *grid, kW, kH);
  FrameSettings s = settingsFor(*grid, test::orbit(*grid, 0.3f, 0.5f, 1.2f), 1.0f);
  s.readDrawList = false;
  std::vector<std::vector<uint8_t>> images;
  for (uint32_t mode = VGEO_MODE_LIT; mode <= VGEO_MODE_PATCH; mode++) {
    s.mode = mode;
    FrameResult r = renderer.renderFrame(s);
    std::vector<uint8_t> mask = test::coverage(r);
    EXPECT_GT(std::count(mask.begin(), mask.end(), 1), 500) << "mode " << mode << " drew almost nothing";
    for (size_t k = 0; k < images.size(); k++)
      EXPECT_NE(images[k], r.rgba) << "mode " << mode << " looks like mode " << k;
    images.push_back(r.rgba);
  }
}

TEST_F(Render, FrozenCutFollowsTheFreezeCamera) {
  GpuRenderer renderer(*vk, *grid, kW, kH);
  Camera a = test::orbit(*grid, 0.3f, 0.5f, 1.2f), b = test::orbit(*grid, 2.0f, 0.2f, 3.0f);
  FrameSettings s = settingsFor(*grid, b, 1.0f);
  s.cullView = makeView(a, kW, kH, grid->bounds);
  s.mode = VGEO_MODE_FROZEN_DIFF;
  FrameResult r = renderer.renderFrame(s);
  std::string difference;
  EXPECT_TRUE(compareCuts(selectSceneCut(*grid, s.cullView, 1.0f), r.drawList, difference)) << difference;
  SceneCut live = selectSceneCut(*grid, s.drawView, 1.0f);
  EXPECT_NE(live.entries.size(), r.drawList.size()) << "the two cameras should pick different cuts";
}

}  // namespace
}  // namespace vgeo

namespace vgeo {
namespace {

TEST_F(Render, ConeCullingDropsOnlyClustersThatFaceAway) {
  // Closed, uniformly scaled instances skip clusters whose every triangle faces away: fewer clusters,
  // the same picture.
  RenderScene withoutCones = *armadillo;
  for (auto& inst : withoutCones.data.instances) inst.flags = 0;
  ASSERT_TRUE(armadillo->data.instances[0].flags & VGEO_INSTANCE_CONE_CULL);
  GpuRenderer culled(*vk, *armadillo, kW, kH), plain(*vk, withoutCones, kW, kH);
  for (float distance : {1.2f, 1.4f}) {
    Camera camera = test::orbit(*armadillo, 0.9f, 0.2f, distance);
    FrameResult a = culled.renderFrame(settingsFor(*armadillo, camera, 1.0f));
    FrameResult b = plain.renderFrame(settingsFor(withoutCones, camera, 1.0f));
    EXPECT_LT(a.counters.drawCount, b.counters.drawCount) << "at " << distance << " radii";
    std::vector<uint8_t> ma = test::coverage(a), mb = test::coverage(b);
    size_t differ = 0;
    for (size_t i = 0; i < ma.size(); i++) differ += ma[i] != mb[i];
    EXPECT_EQ(differ, 0u) << "at " << distance << " radii";
  }
}

// Pixels whose colour differs between two frames.
size_t differingPixels(const FrameResult& a, const FrameResult& b) {
  size_t differ = 0;
  for (size_t i = 0; i + 3 < a.rgba.size(); i += 4)
    differ += a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1] || a.rgba[i + 2] != b.rgba[i + 2];
  return differ;
}

TEST_F(Render, TriangleCullingKeepsThePicture) {
  // Frustum and no-pixel-centre culling never change a pixel: without back-face culling (instances not
  // flagged closed) the image is bit-identical. Back-face culling of closed instances changes only the
  // pixels where a back face showed through a front one (coarse levels may intersect themselves).
  RenderScene open = *grid;
  for (auto& inst : open.data.instances) inst.flags = 0;
  RenderScene mirrored = *single;  // x -> -x: the winding reverses, the outside stays outside
  mirrored.data.instances[0].row0 = -mirrored.data.instances[0].row0;
  mirrored.bounds.x = -mirrored.bounds.x;
  ASSERT_TRUE(mirrored.data.instances[0].flags & VGEO_INSTANCE_CONE_CULL);
  struct Case {
    const RenderScene* scene;
    bool backFaces;
  } cases[] = {{&open, false}, {grid, true}, {&mirrored, true}};
  for (const Case& k : cases) {
    GpuRenderer renderer(*vk, *k.scene, kW, kH);
    for (int view = 0; view < 4; view++) {
      Camera camera = test::orbit(*k.scene, 0.8f + 1.3f * float(view), 0.5f * std::cos(float(view)),
                                  view == 3 ? 0.5f : 1.2f + float(view));
      for (uint32_t mode : {VGEO_MODE_LIT, VGEO_MODE_TRIANGLE}) {
        FrameSettings s = settingsFor(*k.scene, camera, 1.0f);
        s.mode = mode;
        s.patches = false;            // without triangle culling there are no patches: compare triangles with triangles
        s.raster = Raster::Hardware;  // one rasterizer on both sides (SoftwareRasterMatchesHardware compares them)
        FrameResult culled = renderer.renderFrame(s);
        s.triangleCull = false;
        FrameResult all = renderer.renderFrame(s);
        ASSERT_TRUE(culled.complete && all.complete);
        EXPECT_LT(culled.counters.trianglesDrawn, culled.counters.triangles) << "view " << view;
        size_t covered = 0;
        for (uint8_t m : test::coverage(all)) covered += m;
        size_t differ = differingPixels(culled, all);
        if (k.backFaces) {
          // A wrong winding sign would lose the visible side: thousands of pixels.
          EXPECT_LE(double(differ), std::max(4.0, 0.001 * double(covered))) << "view " << view << " mode " << mode;
          if (view < 3) {
            EXPECT_LT(double(culled.counters.trianglesDrawn), 0.6 * culled.counters.triangles) << "view " << view;
          }
        } else {
          EXPECT_EQ(differ, 0u) << "view " << view << " mode " << mode;
        }
      }
    }
  }
}

TEST_F(Render, PackedTriangleCullingListsWhatOneClusterAWorkgroupLists) {
  // cull_small_clusters.comp (64 clusters a workgroup) against cull_triangles.comp (one), forced either
  // way: far views (roots of a few triangles), a close one with patch-drawn clusters, and the view from
  // inside; the same triangles binned the same way make the same ids, so the same pixels.
  GpuRenderer renderer(*vk, *grid, kW, kH);
  for (int view = 0; view < 4; view++) {
    Camera camera = test::orbit(*grid, 0.9f * float(view), 0.4f, view == 0 ? 0.4f : 2.0f + 4.0f * float(view));
    FrameSettings s = settingsFor(*grid, camera, view == 0 ? 0.1f : 2.0f);
    s.mode = VGEO_MODE_TRIANGLE;
    s.packedCullBelow = 0;
    FrameResult one = renderer.renderFrame(s);
    s.packedCullBelow = VGEO_MAX_CLUSTER_TRIANGLES + 1;
    FrameResult packed = renderer.renderFrame(s);
    ASSERT_TRUE(one.complete && packed.complete);
    EXPECT_EQ(one.counters.packedCullDispatch[0], 0u);
    EXPECT_GT(packed.counters.packedCullDispatch[0], 0u);
    EXPECT_EQ(packed.counters.dispatch[0], 0u);
    EXPECT_GT(one.trianglesDrawn, 0u) << "view " << view;
    EXPECT_EQ(packed.trianglesDrawn, one.trianglesDrawn) << "view " << view;
    EXPECT_EQ(packed.softwareTriangles, one.softwareTriangles) << "view " << view;
    EXPECT_EQ(packed.patchesDrawn, one.patchesDrawn) << "view " << view;
    if (view == 0) {
      EXPECT_GT(one.patchesDrawn, 0u);
    }
    EXPECT_EQ(differingPixels(packed, one), 0u) << "view " << view;
  }
}

// The software rasterizer covers the pixels the hardware does with the same triangles: the same cluster
// list drawn each way shows the same triangle (its colour in the triangle view, within the rounding of a
// normal interpolated two ways) in at least 99.9% of the pixels either covers. The rest: samples on an
// edge shared by two triangles at the same depth, or where surfaces meet at equal depth.
TEST_F(Render, SoftwareRasterMatchesHardware) {
  ASSERT_TRUE(GpuRenderer(*vk, *grid, 8, 8).hasSoftwareRaster());
  for (const RenderScene* scene : {grid, armadillo, openLion}) {
    GpuRenderer renderer(*vk, *scene, kW, kH);
    for (int view = 0; view < 3; view++) {
      Camera camera = test::orbit(*scene, 0.4f + 2.1f * float(view), 0.3f, view == 2 ? 0.7f : 1.5f + float(view));
      FrameSettings s = settingsFor(*scene, camera, 1.0f);
      s.mode = VGEO_MODE_TRIANGLE;
      s.patches = false;
      s.raster = Raster::Hardware;
      FrameResult hardware = renderer.renderFrame(s);
      s.raster = Raster::Software;
      FrameResult software = renderer.renderFrame(s);
      ASSERT_TRUE(hardware.complete && software.complete);
      EXPECT_EQ(hardware.softwareTriangles, 0u);
      EXPECT_GT(software.softwareTriangles, hardware.trianglesDrawn / 2) << "view " << view;
      EXPECT_EQ(software.trianglesDrawn, hardware.trianglesDrawn);
      size_t covered = 0, differ = 0;
      for (size_t p = 0; p < hardware.rgba.size(); p += 4) {
        if (!isCovered(&hardware.rgba[p]) && !isCovered(&software.rgba[p])) continue;
        covered++;
        int most = 0;
        for (int k = 0; k < 3; k++)
          most = std::max(most, std::abs(int(hardware.rgba[p + k]) - int(software.rgba[p + k])));
        differ += most > 3;
      }
      EXPECT_GT(covered, 1000u);
      EXPECT_LE(double(differ), 0.001 * double(covered)) << "view " << view << ": " << differ << " of " << covered;
      // Every view through the resolve (the software rasterizer's pixels) with validation on.
      for (uint32_t mode = VGEO_MODE_LIT; mode <= VGEO_MODE_PATCH; mode++) {
        s.mode = mode;
        EXPECT_TRUE(renderer.renderFrame(s).complete);
      }
    }
  }
}

TEST_F(Render, TriangleListOverflowIsReportedAndTheNextFrameIsComplete) {
  FrameSettings s = settingsFor(*grid, test::orbit(*grid, 0.3f, 0.5f, 1.2f), 1.0f);
  GpuRenderer ample(*vk, *grid, kW, kH), tiny(*vk, *grid, kW, kH);
  tiny.setCapacities(1u << 16, 1u << 16, 16, 1u << 16);
  FrameResult want = ample.renderFrame(s), first = tiny.renderFrame(s);
  EXPECT_FALSE(first.complete);
  EXPECT_GT(first.counters.triangleOverflow, 0u);
  EXPECT_GT(tiny.triangleCapacity(), 16u);
  FrameResult next = tiny.renderFrame(s);
  for (int i = 0; i < 4 && !next.complete; i++) next = tiny.renderFrame(s);
  EXPECT_TRUE(next.complete);
  EXPECT_EQ(next.counters.trianglesDrawn, want.counters.trianglesDrawn);
  EXPECT_EQ(differingPixels(next, want), 0u);
}

}  // namespace
}  // namespace vgeo
