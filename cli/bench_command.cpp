// bench_command.cpp: `vgeo bench`, and `vgeo bench cut`: LOD-cut selection measured across scene sizes,
// layouts, cameras, tau and traversal modes (and the CPU reference), one JSON record each.
// bench/plot_cut.py plots them. `bench frame` and `bench build` live in bench_frame.cpp, bench_build.cpp.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "../renderer/gpu_renderer.h"
#include "../renderer/image.h"
#include "bench.h"
#include "commands.h"

namespace vgeo {

std::vector<std::pair<std::string, Camera>> cameraPath(const RenderScene& scene, float fov) {
  glm::vec3 c(scene.bounds), lo = scene.boxMin, hi = scene.boxMax;
  float r = scene.bounds.w, wide = std::max(hi.x - lo.x, hi.z - lo.z);
  float object = scene.data.geometries[0].boundsSphere.w;
  std::vector<std::pair<std::string, Camera>> path;
  Camera far;
  far.eye = c + glm::normalize(glm::vec3(0.3f, 0.5f, 1.0f)) * (6.0f * r);
  far.target = c;
  path.push_back({"far", far});
  path.push_back({"corner", defaultCamera(scene.bounds, lo, hi, fov)});
  Camera inside;
  inside.eye = c + glm::vec3(0.05f * wide, 1.5f * object, 0.03f * wide);
  inside.target = inside.eye + glm::vec3(1.0f, -0.15f, 0.35f);
  path.push_back({"inside", inside});
  const auto& i0 = scene.data.instances[scene.data.instances.size() / 2];
  glm::vec3 at(i0.row0.w, i0.row1.w, i0.row2.w);
  Camera close;
  close.eye = at + glm::vec3(0.4f, 0.6f, 1.4f) * object;
  close.target = at;
  path.push_back({"closeup", close});
  // Surface: 8% of the object's radius in front of its outermost leaf vertex towards the closeup eye
  // (a point of its convex hull, so nothing of it lies in between), looking back at it at an angle:
  // most of what it sees are leaves drawn as patches.
  const shaderio::Geometry& g0 = scene.data.geometries[i0.geometry];
  auto world = [&](uint32_t v) {
    glm::vec4 h(scene.data.position(v), 1.0f);
    return glm::vec3(glm::dot(i0.row0, h), glm::dot(i0.row1, h), glm::dot(i0.row2, h));
  };
  const glm::vec3 toward = glm::normalize(close.eye - at);
  uint32_t outermost = g0.vertexOffset;
  for (uint32_t v = g0.vertexOffset; v < g0.vertexOffset + g0.vertexCount; v++)
    if (glm::dot(world(v) - at, toward) > glm::dot(world(outermost) - at, toward)) outermost = v;
  const float reach = 0.015f * object * i0.maxScale;
  Camera surface;
  surface.eye = world(outermost) + toward * reach;
  surface.target =
      world(outermost) - toward * reach + glm::normalize(glm::cross(toward, glm::vec3(0.0f, 1.0f, 0.0f))) * reach;
  path.push_back({"surface", surface});
  Camera away;
  away.eye = glm::vec3(hi.x, c.y + object, hi.z) + glm::vec3(0.1f) * wide;
  away.target = away.eye + glm::vec3(1.0f, 0.0f, 1.0f);
  path.push_back({"away", away});
  // Ground: at the height of the objects' centres, just outside the rows of the near (-z) edge, looking
  // along them; above: high over the near edge, looking down across all of it.
  Camera ground;
  ground.eye = glm::vec3(c.x + 0.013f * wide, c.y, lo.z - 4.0f * object);
  ground.target = ground.eye + glm::vec3(0.08f, -0.02f, 1.0f);
  path.push_back({"ground", ground});
  Camera above;
  above.eye = c + glm::vec3(0.0f, 0.6f * wide, -0.45f * wide);
  above.target = c;
  path.push_back({"above", above});
  for (auto& [name, cam] : path) cam.fovYDegrees = fov;
  return path;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

namespace {

struct BenchArgs {
  std::string input, output, sizes = "1,10,100,1000,10000,100000", layouts = "grid,scatter", taus = "1,4",
                             traversals = "persistent,levels,flat,cpu", size = "1920x1080", device;
  uint32_t frames = 5, cpuMaxInstances = 1000, flatMaxInstances = 10000, workgroups = 0,
           sweepBudget = kDefaultSweepBudget;
  bool profileWorkers = false;
  std::string instanceCulling = "auto";
  // The cut alone by default: with occlusion culling a frame selects twice (early and late pass) and lists
  // only what the depth pyramid leaves, a different quantity from the cut the CPU reference selects.
  std::string occlusion = "off";
  float fov = 60.0f;
};

void runBenchCut(const BenchArgs& a) {
  uint32_t width = 0, height = 0;
  if (!parseSize(a.size, width, height)) throw std::runtime_error("--size: expected WxH");
  RenderScene base = loadRenderScene(a.input);
  VulkanContext vk({a.device, false});
  nlohmann::ordered_json records = nlohmann::json::array();
  std::vector<Occlusion> occlusions;
  for (const std::string& o : parseList<std::string>(a.occlusion))
    occlusions.push_back(occlusionNamed("--occlusion", o));
  for (const std::string& layout : parseList<std::string>(a.layouts)) {
    if (layout != "grid" && layout != "scatter") throw std::runtime_error("--layouts: grid or scatter");
    const BenchLayout benchLayout = benchLayoutNamed(layout);
    for (uint32_t count : parseList<uint32_t>(a.sizes)) {
      RenderScene scene = makeBenchScene(base, count, benchLayout, 7);
      GpuRenderer renderer(vk, scene, width, height);
      if (a.workgroups) renderer.setPersistentWorkgroups(a.workgroups);
      // The CPU reference last, after the GPU records (its seconds of host work let the GPU clock down).
      std::vector<std::string> modes = parseList<std::string>(a.traversals);
      std::stable_partition(modes.begin(), modes.end(), [](const std::string& m) { return m != "cpu"; });
      bool sceneWarm = false;
      for (const std::string& mode : modes)
        for (const auto& [cameraName, camera] : cameraPath(scene, a.fov))
          for (float tau : parseList<float>(a.taus))
            for (Occlusion occlusion : occlusions) {
              if (mode == "cpu" && occlusion != occlusions.front()) continue;
              FrameSettings s;
              s.drawView = s.cullView = makeView(camera, width, height, scene.bounds);
              s.tau = tau;
              s.sweepBudget = a.sweepBudget;
              s.instanceCulling = instanceCullingNamed(a.instanceCulling);
              s.occlusion = occlusion;
              // On a GPU every frame also draws (not timed: the traversal has its own timestamps): selection
              // alone left an H100 idle most of the time, its clock dropped within ~100 ms, and the same
              // traversal then measured 2-4x slower. lavapipe has no clocks to keep up: selection only.
              s.draw = !vk.isLavapipe();
              s.readImage = false;
              nlohmann::ordered_json r;
              r["layout"] = layout;
              r["instances"] = count;
              r["camera"] = cameraName;
              r["tau"] = tau;
              r["mode"] = mode;
              if (mode != "cpu") r["occlusion_setting"] = occlusionName(occlusion);
              if (mode == "cpu") {
                if (uint64_t(count) > a.cpuMaxInstances) continue;
                std::vector<double> ms;
                SceneCut cut;
                for (uint32_t f = 0; f < std::max(1u, a.frames / 2); f++) {
                  auto start = std::chrono::steady_clock::now();
                  cut = selectSceneCut(scene, s.cullView, tau);
                  ms.push_back(
                      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
                }
                r["traversal_ms"] = median(ms);
                r["timing"] = "host";
                r["visible_clusters"] = cut.entries.size() + cut.borderline.size();
              } else {
                s.traversal = traversalNamed("--traversals", mode);
                if (s.traversal == Traversal::Flat && count > a.flatMaxInstances) continue;
                FrameResult f = renderer.renderFrame(s);  // warm-up (and growth after an overflow)
                while (!f.complete) f = renderer.renderFrame(s);
                // At least 3 more frames and 300 ms: a GPU that idled (during the CPU reference or the scene's
                // upload) measured up to 4x slow in its first frames back, and 100 ms of frames were not
                // always enough to bring its clock back (H100). The first record of a scene follows the last
                // scene's CPU reference (up to ~30 s of host work): 2 s there (300 ms left it 2x slow).
                auto warm = std::chrono::steady_clock::now();
                const auto warmFor = std::chrono::milliseconds(sceneWarm ? 300 : 2000);
                for (int i = 0; i < 3 || std::chrono::steady_clock::now() - warm < warmFor; i++)
                  renderer.renderFrame(s);
                sceneWarm = true;
                std::vector<double> ms, cullMs;
                uint32_t twoPass = 0;
                for (uint32_t i = 0; i < a.frames; i++) {
                  f = renderer.renderFrame(s);
                  ms.push_back(f.instanceCullMs + f.traversalMs);  // the whole selection (both passes' with occlusion)
                  cullMs.push_back(f.instanceCullMs);
                  twoPass += f.occlusion ? 1u : 0u;
                }
                r["two_pass_frames"] = twoPass;
                // What the cut costs per pixel it covers: one more frame, its picture read back (not timed).
                FrameSettings picture = s;
                picture.readImage = picture.draw = true;
                const FrameResult p = renderer.renderFrame(picture);
                const uint64_t covered = coveredPixels(p.rgba);
                r["pixels_covered"] = covered;
                r["triangles_listed_per_pixel"] = covered ? double(p.counters.triangles) / double(covered) : 0.0;
                r["triangles_drawn_per_pixel"] = covered ? double(p.trianglesDrawn) / double(covered) : 0.0;
                r["traversal_ms"] = median(ms);
                r["instance_cull_ms"] =
                    median(cullMs);  // part of traversal_ms (the counter reset when culled in the traversal)
                addFrameCounters(r, f, renderer, vk);
                if (s.traversal == Traversal::Persistent) {
                  r["workgroups"] = renderer.persistentWorkgroups();
                  r["sweep_budget"] = a.sweepBudget;
                  r["swept_tests"] = f.counters.sweptTests;
                  // One more frame, profiled (not timed: the stamps cost time of their own).
                  if (a.profileWorkers && renderer.canProfileWorkers()) {
                    FrameSettings p = s;
                    p.profileWorkers = true;
                    r["worker_profile"] =
                        summarizeWorkerProfile(renderer.renderFrame(p).workerProfile, renderer.persistentWorkgroups());
                  }
                }
              }
              if (mode == "cpu") {
                r["device"] = "host CPU";
                r["driver"] = "";
              }
              r["width"] = width;
              r["height"] = height;
              r["commit"] = VGEO_COMMIT;
              std::fprintf(stderr, "%-7s %6u instances %-8s tau %-3g %-10s %-4s %9.3f ms %8s clusters\n",
                           layout.c_str(), count, cameraName.c_str(), tau, mode.c_str(),
                           mode == "cpu" ? "" : occlusionName(occlusion), r["traversal_ms"].get<double>(),
                           std::to_string(r["visible_clusters"].get<uint64_t>()).c_str());
              records.push_back(r);
            }
    }
  }
  writeJson(a.output, records, 1);
}

}  // namespace

void addBenchCommand(CLI::App& app, int& exitCode) {
  auto* bench = app.add_subcommand("bench", "Benchmarks");
  bench->require_subcommand(1);
  auto* cut =
      bench->add_subcommand("cut", "LOD-cut selection across scene sizes, layouts, cameras, tau and traversal modes");
  auto a = std::make_shared<BenchArgs>();
  cut->add_option("input", a->input, ".vgeo whose first geometry is instanced")->required();
  cut->add_option("-o,--output", a->output, "JSON records")->required();
  cut->add_option("--sizes", a->sizes, "Instance counts")->capture_default_str();
  cut->add_option("--layouts", a->layouts, "grid and/or scatter")->capture_default_str();
  cut->add_option("--taus", a->taus, "Allowed projected errors, pixels")->capture_default_str();
  cut->add_option("--traversals", a->traversals, "persistent, levels, flat, cpu")->capture_default_str();
  cut->add_option("--frames", a->frames, "Measured frames per record (median)")->capture_default_str();
  cut->add_option("--size", a->size, "Viewport WxH")->capture_default_str();
  cut->add_option("--cpu-max-instances", a->cpuMaxInstances, "Largest scene the CPU reference runs on")
      ->capture_default_str();
  cut->add_option("--flat-max-instances", a->flatMaxInstances, "Largest scene the flat traversal runs on")
      ->capture_default_str();
  cut->add_option("--workgroups", a->workgroups, "Persistent traversal workgroups (default: the renderer's)")
      ->check(CLI::Range(1u, 65535u));  // a dispatch's most workgroups that every device runs
  cut->add_option("--sweep-budget", a->sweepBudget,
                  "Persistent traversal: cluster tests a frame may sweep instead of walking (0: none)")
      ->capture_default_str();
  addInstanceCullingOption(cut, a->instanceCulling);
  cut->add_option("--occlusion", a->occlusion,
                  "Occlusion culling off, on and/or auto, a record each (off: the cut alone, as the CPU selects it)")
      ->capture_default_str();
  cut->add_flag("--profile-workers", a->profileWorkers,
                "Persistent records: one more frame with the workers' iterations timed in the shader (needs "
                "VK_KHR_shader_clock)");
  addDeviceOption(cut, a->device);
  cut->callback([a, &exitCode] {
    runBenchCut(*a);
    exitCode = 0;
  });
  addBenchFrameCommand(*bench, exitCode);
  addBenchBuildCommand(*bench, exitCode);
}

}  // namespace vgeo
