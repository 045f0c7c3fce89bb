// render_command.cpp: `vgeo render INPUT -o OUT.png`: one frame of the GPU renderer, its stats, and
// optionally the comparison with the CPU reference cut.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../common/input_error.h"
#include "../renderer/debug_modes.h"
#include "../renderer/gpu_renderer.h"
#include "../renderer/image.h"
#include "commands.h"
#include "options.h"
#include "render_path.h"
#include "view_script.h"

namespace vgeo {
namespace {

struct RenderArgs {
  std::string input, output, stats, camera, freezeCamera, light, path, mode = "lit", traversal = "persistent",
                                                                       size = "1280x720", device;
  float fov = 60.0f, tau = 1.0f;
  uint32_t grid = 1, frames = 2, queueCapacity = 0, drawCapacity = 0, triangleCapacity = 0, workgroups = 0,
           cullLanes = 0;
  uint32_t pyramidLevel = 3;
  uint32_t sweepBudget = kDefaultSweepBudget, maxFrameMemoryMiB = kDefaultFrameMemoryMiB, deviceMemoryMiB = 0;
  uint32_t packedCullBelow = kDefaultPackedCullBelow;
  std::string instanceCulling = "auto", raster = "auto", layout = "grid", occlusion = "auto";
  bool compareCpu = false, validate = false, noTriangleCull = false, noPatches = false, noOcclusion = false;
};

// The frame's settings from the command line (views of the draw and cull cameras).
FrameSettings frameSettings(const RenderArgs& a, const RenderScene& scene, const Camera& camera,
                            const Camera& cullCamera, uint32_t width, uint32_t height) {
  FrameSettings settings;
  settings.drawView = makeView(camera, width, height, scene.bounds);
  settings.cullView = makeView(cullCamera, width, height, scene.bounds);
  settings.tau = a.tau;
  settings.mode = debugModeNamed(a.mode)->mode;  // checked by the option
  settings.sweepBudget = a.sweepBudget;
  settings.cullLanes = a.cullLanes;
  settings.instanceCulling = instanceCullingNamed(a.instanceCulling);
  settings.traversal = traversalNamed("--traversal", a.traversal);
  settings.readDrawList = a.compareCpu;
  settings.triangleCull = !a.noTriangleCull;
  settings.patches = !a.noPatches;
  settings.raster = rasterNamed("--raster", a.raster);
  settings.packedCullBelow = a.packedCullBelow;
  settings.occlusion = a.noOcclusion ? Occlusion::Off : occlusionNamed("--occlusion", a.occlusion);
  if (!a.light.empty()) settings.light = parseDirectionOption("--light", a.light);
  settings.pyramidViewLevel = a.pyramidLevel;
  return settings;
}

// Views the shaders can use: finite in float (an eye at 3e19 or --fov 1e-20 is finite in double, not in the
// view-projection the GPU multiplies by).
void checkViews(const RenderArgs& a, const FrameSettings& settings) {
  const char* cause =
      "makes a view that is not finite in float: the eye too far from the scene or the field of view too narrow";
  if (!finiteView(settings.drawView)) throw UsageError(a.camera.empty() ? "--fov" : "--camera", cause);
  if (!finiteView(settings.cullView)) throw UsageError("--freeze-camera", cause);
}

struct RenderRun {
  FrameResult result;  // the last frame's
  uint32_t frames = 0, queueOverflows = 0, drawOverflows = 0, triangleOverflows = 0, patchOverflows = 0;
  // The frames' passes after the first kUntimedFrames (lists grown, caches warm): as `vgeo view` times them.
  uint32_t timedFrames = 0;
  double timedMs = 0.0;
};

// Frames until one is complete (an overflow grows the buffers for the next); the first frames warm the
// shader cache (docs/gpu-notes.md, 4), the last one is reported.
RenderRun renderUntilComplete(GpuRenderer& renderer, const FrameSettings& settings, uint32_t frames) {
  RenderRun run;
  for (uint32_t f = 0; f < std::max(frames, 1u) || !run.result.complete; f++) {
    if (f >= frames + 12)
      throw std::runtime_error("frames keep overflowing after growing the buffers and the workers 12 times");
    run.result = renderer.renderFrame(settings);
    run.frames++;
    if (run.frames > kUntimedFrames) {
      run.timedFrames++;
      run.timedMs += run.result.frameMs;
    }
    const auto& c = run.result.counters;
    if (run.result.workersRanOut) {
      std::fprintf(stderr, "frame %u: the traversal's workers ran out of their iteration budget; %u workers next\n",
                   run.frames, renderer.persistentWorkgroups());
    } else if (!run.result.complete) {
      run.queueOverflows += c.queueOverflow;
      run.drawOverflows += c.drawOverflow;
      run.triangleOverflows += c.triangleOverflow;
      run.patchOverflows += c.patchOverflow;
      std::fprintf(stderr,
                   "overflow in frame %u: %u queue items, %u draw entries, %u triangles and %u patches did not fit; "
                   "grown to %u queue items, %u draw entries, %u triangles, %u patches\n",
                   run.frames, c.queueOverflow, c.drawOverflow, c.triangleOverflow, c.patchOverflow,
                   renderer.queueCapacity(), renderer.drawCapacity(), renderer.triangleCapacity(),
                   renderer.patchCapacity());
    }
  }
  return run;
}

// The frame statistics of `--stats` (docs/cli.md lists the fields).
nlohmann::ordered_json frameStats(const RenderArgs& a, const RenderScene& scene, const Camera& camera,
                                  const FrameSettings& settings, const RenderRun& run, const GpuRenderer& renderer,
                                  const VulkanContext& vk, uint32_t width, uint32_t height) {
  const FrameResult& result = run.result;
  const auto& c = result.counters;
  const uint64_t covered = coveredPixels(result.rgba);
  nlohmann::ordered_json j;
  j["width"] = width;
  j["height"] = height;
  j["tau"] = a.tau;
  j["mode"] = a.mode;
  j["traversal"] = a.traversal;
  j["instances_total"] = scene.data.instances.size();
  j["virtual_triangles"] = scene.virtualTriangles;
  addFrameCounters(j, result, renderer, vk);
  j["triangle_cull"] = settings.triangleCull;
  j["patches"] = settings.patches && settings.triangleCull;
  j["pixels_covered"] = covered;
  j["triangles_per_covered_pixel"] = covered ? double(result.trianglesDrawn) / double(covered) : 0.0;
  j["cut_triangles_per_covered_pixel"] = covered ? double(c.triangles) / double(covered) : 0.0;
  j["queue_overflows"] = run.queueOverflows;
  j["draw_overflows"] = run.drawOverflows;
  j["triangle_overflows"] = run.triangleOverflows;
  j["patch_overflows"] = run.patchOverflows;
  j["persistent_workgroups"] = renderer.persistentWorkgroups();
  j["swept_tests"] = c.sweptTests;
  j["instance_cull_ms"] = result.instanceCullMs;
  j["traversal_ms"] = result.traversalMs;
  j["triangle_cull_ms"] = result.triangleCullMs;
  j["raster_ms"] = result.rasterMs;
  j["draw_ms"] = result.drawMs;
  j["resolve_ms"] = result.resolveMs;
  j["pyramid_ms"] = result.pyramidMs;
  j["frame_ms"] = result.frameMs;
  j["frame_mean_ms"] = run.timedFrames ? run.timedMs / run.timedFrames : result.frameMs;  // past the first 5
  j["frames"] = run.frames;
  j["camera"] = cameraOption(camera);
  if (a.compareCpu) {
    // With occlusion culling the GPU lists what the depth pyramid did not hide: a subset of the cut.
    SceneCut reference = selectSceneCut(scene, settings.cullView, a.tau);
    std::string difference;
    bool equal = compareCuts(reference, result.drawList, difference, result.occlusion);
    j["cpu_cut_equal"] = equal;  // with occlusion culling: a subset
    j["cpu_clusters"] = reference.entries.size();
    j["borderline_clusters"] = reference.borderline.size();
    if (!equal) j["cpu_cut_difference"] = difference;
  }
  return j;
}

void printSummary(const RenderArgs& a, const RenderScene& scene, const RenderRun& run, const GpuRenderer& renderer,
                  const VulkanContext& vk, const nlohmann::ordered_json& j, uint32_t width, uint32_t height) {
  const FrameResult& result = run.result;
  const auto& c = result.counters;
  std::printf(
      "%s: %ux%u on %s, %s traversal, tau %g: %u of %zu instances visible, %u clusters, %u triangles in the cut of "
      "%llu virtual, %u drawn (%.2f a covered pixel, %u in software); instance culling %.2f ms, traversal %.2f "
      "ms, triangle culling %.2f ms, software raster %.2f ms, draw %.2f ms, resolve %.2f ms, frame %.2f ms (%s)\n",
      a.output.c_str(), width, height, vk.deviceName().c_str(), a.traversal.c_str(), a.tau, c.visibleInstances,
      scene.data.instances.size(), std::min(c.drawCount, renderer.drawCapacity()), c.triangles,
      (unsigned long long)scene.virtualTriangles, result.trianglesDrawn, j["triangles_per_covered_pixel"].get<double>(),
      result.softwareTriangles, result.instanceCullMs, result.traversalMs, result.triangleCullMs, result.rasterMs,
      result.drawMs, result.resolveMs, result.frameMs, result.timing.c_str());
  if (result.occlusion)
    std::printf(
        "occlusion culling: %u clusters drawn early; hidden: %u instances, %u nodes, %u clusters; depth "
        "pyramid %.2f ms\n",
        c.drawBase, c.occludedInstances, c.occludedNodes, c.occludedClusters, result.pyramidMs);
  if (a.compareCpu)
    std::printf("cpu cut: %s (%zu clusters, %zu borderline)%s\n",
                !j["cpu_cut_equal"].get<bool>() ? "DIFFERENT"
                : result.occlusion              ? "a subset (occlusion culling)"
                                                : "equal",
                size_t(j["cpu_clusters"]), size_t(j["borderline_clusters"]),
                j.contains("cpu_cut_difference") ? (": " + j["cpu_cut_difference"].get<std::string>()).c_str() : "");
}

int runRender(const RenderArgs& a) {
  // The command line first, all of it, before anything is loaded or drawn.
  uint32_t width = 0, height = 0;
  if (!parseSize(a.size, width, height))
    throw UsageError("--size", "expected WxH with both in 1..16384, e.g. 1280x720 (got '" + a.size + "')");
  traversalNamed("--traversal", a.traversal);
  if (rasterNamed("--raster", a.raster) == Raster::Software && a.noTriangleCull)
    throw UsageError("--raster", "software needs triangle culling, which bins the triangles (drop --no-triangle-cull)");
  std::vector<ViewEvent> script;
  if (a.path.empty()) {
    checkOutputPath("--output", a.output, {a.input}, ".png");
  } else {  // -o names a folder for the frames
    if (!std::filesystem::is_directory(a.output))
      throw UsageError("--output", "with --path, a folder that exists for the frames (got '" + a.output + "')");
    script = readViewScript(a.path, a.fov, {a.input, a.path});
  }
  if (!a.stats.empty()) checkOutputPath("--stats", a.stats, {a.input, a.output});
  std::optional<Camera> camera, cullCamera;
  if (!a.camera.empty()) camera = parseCameraOption("--camera", a.camera, a.fov);
  if (!a.freezeCamera.empty()) cullCamera = parseCameraOption("--freeze-camera", a.freezeCamera, a.fov);
  if (!a.light.empty()) parseDirectionOption("--light", a.light);

  // A grid copies the whole scene; a forest packs N x N instances of its first geometry in rows.
  RenderScene scene = loadLaidOutScene(a.input, a.grid, a.layout);
  if (!camera) camera = sceneCamera(scene, a.fov, float(width) / float(height));
  camera->fovYDegrees = a.fov;
  if (!cullCamera) cullCamera = camera;

  VulkanContext vk({a.device, a.validate, uint64_t(a.deviceMemoryMiB) << 20});
  std::optional<GpuRenderer> made;
  try {
    made.emplace(vk, scene, width, height);
  } catch (const SceneTooLargeError& e) {
    throw SceneTooLargeError(a.input + ": " + e.what());
  }
  GpuRenderer& renderer = *made;
  renderer.setFrameMemoryLimit(uint64_t(a.maxFrameMemoryMiB) << 20);
  if (a.workgroups) renderer.setPersistentWorkgroups(a.workgroups);
  if (a.queueCapacity || a.drawCapacity || a.triangleCapacity)
    renderer.setCapacities(a.queueCapacity ? a.queueCapacity : renderer.queueCapacity(),
                           a.drawCapacity ? a.drawCapacity : renderer.drawCapacity(),
                           a.triangleCapacity ? a.triangleCapacity : renderer.triangleCapacity(),
                           renderer.patchCapacity());
  const FrameSettings settings = frameSettings(a, scene, *camera, *cullCamera, width, height);
  checkViews(a, settings);
  if (settings.raster == Raster::Software && !renderer.hasSoftwareRaster())
    throw UsageError("--raster", "software needs 64-bit buffer atomics (shaderBufferInt64Atomics), which " +
                                     vk.deviceName() + " lacks, and a picture of at most " +
                                     std::to_string(vk.properties().limits.maxStorageBufferRange / 8) + " pixels");
  if (settings.instanceCulling == InstanceCulling::InTraversal && !renderer.cullsInTraversal(settings))
    throw UsageError("--instance-culling", "traversal needs the persistent traversal, culling lanes " +
                                               std::to_string(VGEO_CULL_INSTANCE_LANES) + " and at most " +
                                               std::to_string(GpuRenderer::kCullInTraversalMaxPerWorker) +
                                               " instances a worker (" +
                                               std::to_string(renderer.persistentWorkgroups()) + " workers)");

  if (!a.path.empty())
    return renderPath(script, a.output, vk, scene, made, settings, *camera,
                      a.freezeCamera.empty() ? std::nullopt : cullCamera);
  const RenderRun run = renderUntilComplete(renderer, settings, a.frames);
  writePng(a.output, width, height, run.result.rgba);
  const nlohmann::ordered_json j = frameStats(a, scene, *camera, settings, run, renderer, vk, width, height);
  if (!a.stats.empty()) writeJson(a.stats, j, 2);  // before the summary: a failed write is the one line printed
  printSummary(a, scene, run, renderer, vk, j, width, height);
  if (a.camera.empty()) std::printf("camera: --camera %s\n", cameraOption(*camera).c_str());  // to pass it back
  if (vk.validationMessages() > 0) {
    std::fprintf(stderr, "validation: %u messages\n", vk.validationMessages());
    return kExitValidation;
  }
  if (a.compareCpu && !j["cpu_cut_equal"].get<bool>()) return kExitCutDiffers;
  return kExitOk;
}

}  // namespace

void addSceneViewOptions(CLI::App* cmd, float& fov, float& tau, std::string& mode, uint32_t& grid,
                         std::string& layout) {
  cmd->add_option("--fov", fov, "Vertical field of view, degrees")
      ->capture_default_str()
      ->check(finiteBetween(0.0, 180.0));
  cmd->add_option("--tau", tau, "Allowed projected error, pixels (a tau below what the leaves reach draws the leaves)")
      ->capture_default_str()
      ->check(finiteBetween(0.0, INFINITY));
  std::vector<std::string> modes;
  for (const DebugMode& m : kDebugModes) modes.push_back(m.name);
  cmd->add_option("--mode", mode, "Debug view")->capture_default_str()->check(CLI::IsMember(modes));
  cmd->add_option("--grid", grid, "N x N instances of the input")->capture_default_str()->check(CLI::Range(1u, 4096u));
  cmd->add_option("--layout", layout,
                  "grid: --grid copies of the input side by side; forest: N x N instances of its first geometry "
                  "packed in rows, jittered, turned and scaled (a dense scene for occlusion culling)")
      ->check(CLI::IsMember({"grid", "forest"}))
      ->capture_default_str();
}

RenderScene loadLaidOutScene(const std::string& input, uint32_t grid, const std::string& layout) {
  return layout == "forest" ? makeBenchScene(loadRenderScene(input), grid * grid, BenchLayout::Forest, 7)
                            : loadRenderScene(input, grid);
}

void addRenderCommand(CLI::App& app, int& exitCode) {
  auto* cmd = app.add_subcommand("render", "Render a .vgeo or a scene file (JSON) to a PNG with the GPU LOD renderer");
  auto a = std::make_shared<RenderArgs>();
  cmd->add_option("input", a->input, ".vgeo file or scene file (.json)")->required();
  cmd->add_option("-o,--output", a->output, "Output PNG")->required();
  cmd->add_option("--size", a->size, "Image size WxH")->capture_default_str();
  cmd->add_option("--camera", a->camera, "eye_x,eye_y,eye_z,target_x,target_y,target_z (default: frames the scene)");
  cmd->add_option("--pyramid-level", a->pyramidLevel,
                  "--mode pyramid: the level shown (1 covers 2 x 2 pixels a texel; past the top, the top)")
      ->capture_default_str()
      ->check(CLI::Range(1u, 31u));
  cmd->add_option("--path", a->path,
                  "A viewer script (docs/viewer.md) played without a window: -o is then a folder, a PNG a frame");
  cmd->add_option("--light", a->light,
                  "x,y,z: the direction light comes from (default: a fixed light from above, right and front)");
  addSceneViewOptions(cmd, a->fov, a->tau, a->mode, a->grid, a->layout);
  addTraversalOption(cmd, a->traversal);
  cmd->add_option("--freeze-camera", a->freezeCamera,
                  "Select and cull with this camera (six numbers), draw from --camera");
  cmd->add_flag("--compare-cpu", a->compareCpu,
                "Compare the GPU draw list with the CPU reference cut (exit 4 if they differ)");
  cmd->add_option("--stats", a->stats, "Write frame statistics as JSON to this file");
  addDeviceOption(cmd, a->device);
  cmd->add_flag("--validate", a->validate,
                "Khronos validation layer with synchronization validation (exit 3 on any message)");
  cmd->add_option("--frames", a->frames, "Frames to render; the last is reported (the first warms shader caches)")
      ->capture_default_str()
      ->check(CLI::Range(1u, 100000u));
  cmd->add_option("--max-frame-memory", a->maxFrameMemoryMiB,
                  "MiB the frame's growing lists (queue, draw, triangle, patch) may take; a cut that needs more stops "
                  "with exit 5")
      ->capture_default_str()
      ->check(CLI::Range(1u, 1u << 20));
  cmd->add_option("--device-memory", a->deviceMemoryMiB,
                  "MiB of device memory to plan with: a scene whose arrays need more is refused (exit 5), as on a "
                  "GPU of that size (default: the device's)")
      ->check(CLI::Range(1u, 1u << 30));
  cmd->add_option("--queue-capacity", a->queueCapacity, "Initial traversal queue capacity, items (debugging overflow)");
  cmd->add_option("--draw-capacity", a->drawCapacity, "Initial draw list capacity, clusters (debugging overflow)");
  cmd->add_option("--triangle-capacity", a->triangleCapacity,
                  "Initial triangle list capacity, triangles (debugging overflow)");
  cmd->add_flag("--no-triangle-cull", a->noTriangleCull,
                "Draw every triangle of the listed clusters (default: drop those that cannot make a fragment first); "
                "implies --no-patches");
  cmd->add_option("--occlusion", a->occlusion,
                  "Two passes, the second culled against the depth of what the first drew: auto (while they hide a "
                  "tenth of what a frame draws, probed every few frames), on, off (one pass, culled by frustum, cone "
                  "and triangle only)")
      ->check(CLI::IsMember({"auto", "on", "off"}))
      ->capture_default_str();
  cmd->add_flag("--no-occlusion", a->noOcclusion, "The same as --occlusion off");
  cmd->add_flag("--no-patches", a->noPatches,
                "Draw leaf clusters as their triangles even where their chord error projects above tau (default: "
                "tessellated limit-surface patches)");
  cmd->add_option("--workgroups", a->workgroups,
                  "Persistent traversal workgroups (default: as many as the device runs at once)")
      ->check(CLI::Range(1u, 65535u));  // a dispatch's most workgroups that every device runs
  cmd->add_option("--sweep-budget", a->sweepBudget,
                  "Persistent traversal: cluster tests a frame may sweep instead of walking (0: none)")
      ->capture_default_str();
  cmd->add_option("--cull-lanes", a->cullLanes,
                  "Lanes instance culling gives an instance, 1 or " + std::to_string(VGEO_CULL_INSTANCE_LANES) +
                      " (default: the renderer's; sweeps need " + std::to_string(VGEO_CULL_INSTANCE_LANES) + ")")
      ->check(CLI::IsMember({1u, uint32_t(VGEO_CULL_INSTANCE_LANES)}));
  addInstanceCullingOption(cmd, a->instanceCulling);
  addPackedCullOption(cmd, a->packedCullBelow);
  cmd->add_option(
         "--raster", a->raster,
         "Rasterizer of the listed triangles: auto (small ones in compute where the device has 64-bit "
         "atomics, the rest in hardware), hardware, or software (every one in front of the near plane it can take)")
      ->check(CLI::IsMember({"auto", "hardware", "software"}))
      ->capture_default_str();
  cmd->callback([a, &exitCode] { exitCode = runRender(*a); });
}

}  // namespace vgeo
