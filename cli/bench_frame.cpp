// bench_frame.cpp: `vgeo bench frame`: whole frames split into their passes (instance culling,
// traversal, triangle culling, software raster, the render pass with the patch draw), for a scene at
// several grid sizes, viewport sizes and cameras, in variants: for each rasterizer of --rasters, triangle
// culling with patches (the default) and with leaves as triangles; then neither (hardware). Medians over frames after
// warm-up; one JSON record each.
#include <chrono>
#include <cstdio>
#include <numeric>

#include <nlohmann/json.hpp>

#include "../renderer/gpu_renderer.h"
#include "../renderer/image.h"
#include "bench.h"
#include "commands.h"
#include "options.h"

namespace vgeo {
namespace {

// Frames before each variant's records, for the GPU's clocks to rise. On an idle H100 it shortens the
// first records' lag but does not cure it (bench/README.md): compare runs after the first.
constexpr double kWarmUpSeconds = 0.3;

struct FrameBenchArgs {
  std::string input, output, grids = "32", sizes = "1280x720,1920x1080", cameras = "corner,inside",
                             traversal = "persistent", device, rasters = "auto,hardware", layout = "grid",
                             occlusion = "on,off";
  uint32_t frames = 5, pathFrames = 60;
  uint32_t packedCullBelow = kDefaultPackedCullBelow;
  float fov = 60.0f, tau = 1.0f;
};

// The fly-through: `count` poses from the ground camera to the one above, moving and turning.
std::vector<Camera> flyThrough(const std::vector<std::pair<std::string, Camera>>& path, uint32_t count) {
  auto named = [&](const char* name) {
    return std::find_if(path.begin(), path.end(), [&](const auto& p) { return p.first == name; })->second;
  };
  const Camera from = named("ground"), to = named("above");
  std::vector<Camera> poses;
  for (uint32_t i = 0; i < count; i++) {
    const float t = count > 1 ? float(i) / float(count - 1) : 0.0f, ease = t * t * (3.0f - 2.0f * t);
    Camera c = from;
    c.eye = glm::mix(from.eye, to.eye, ease);
    c.target = glm::mix(from.target, to.target, t);
    poses.push_back(c);
  }
  return poses;
}

struct Variant {
  bool triangleCull, patches;
  std::string raster;
};

// One record: frames of `renderer` from `poses` (one camera: a.frames frames from it; a fly-through: a
// frame from each pose, the occlusion state carried from one to the next) in `variant`, medians.
nlohmann::ordered_json measureFrames(const FrameBenchArgs& a, GpuRenderer& renderer, const VulkanContext& vk,
                                     const RenderScene& scene, const std::vector<Camera>& poses, const Variant& variant,
                                     Occlusion occlusion) {
  const uint32_t width = renderer.width(), height = renderer.height();
  const bool triangleCull = variant.triangleCull, patches = variant.patches;
  FrameSettings s;
  s.raster = rasterNamed("--rasters", variant.raster);
  s.drawView = s.cullView = makeView(poses[0], width, height, scene.bounds);
  s.tau = a.tau;
  s.traversal = traversalNamed("--traversal", a.traversal);
  s.triangleCull = triangleCull;
  s.patches = patches;
  s.packedCullBelow = a.packedCullBelow;
  s.occlusion = occlusion;
  // Warm-up and growth after an overflow; this frame's image gives the pixels covered, and the patch
  // view's the pixels the patches cover.
  FrameResult f = renderer.renderFrame(s);
  while (!f.complete) f = renderer.renderFrame(s);
  const uint64_t covered = coveredPixels(f.rgba);
  uint64_t patchCovered = 0;
  if (patches) {
    s.mode = VGEO_MODE_PATCH;
    patchCovered = patchPixels(renderer.renderFrame(s).rgba);
    s.mode = VGEO_MODE_LIT;
  }
  s.readImage = false;  // measured frames: no image copy
  // GPUs raise their clocks only under load: frames for a while before the records.
  const auto warmStart = std::chrono::steady_clock::now();
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - warmStart).count() < kWarmUpSeconds)
    renderer.renderFrame(s);
  std::vector<double> cull, traverse, triangles, raster, draw, resolve, pyramid, frame, clusters;
  const uint32_t count = poses.size() > 1 ? uint32_t(poses.size()) : a.frames;
  for (uint32_t i = 0; i < count; i++) {
    if (poses.size() > 1) s.drawView = s.cullView = makeView(poses[i], width, height, scene.bounds);
    f = renderer.renderFrame(s);
    cull.push_back(f.instanceCullMs);
    traverse.push_back(f.traversalMs);
    triangles.push_back(f.triangleCullMs);
    raster.push_back(f.rasterMs);
    draw.push_back(f.drawMs);
    resolve.push_back(f.resolveMs);
    pyramid.push_back(f.pyramidMs);
    frame.push_back(f.frameMs);
    clusters.push_back(std::min(f.counters.drawCount, renderer.drawCapacity()));
  }
  nlohmann::ordered_json r;
  r["input"] = a.input;
  r["layout"] = a.layout;
  r["instances"] = scene.data.instances.size();
  r["virtual_triangles"] = scene.virtualTriangles;
  r["width"] = width;
  r["height"] = height;
  r["tau"] = a.tau;
  r["traversal"] = a.traversal;
  r["triangle_cull"] = triangleCull;
  r["patches"] = patches;
  r["raster"] = variant.raster;
  r["instance_cull_ms"] = median(cull);
  r["traversal_ms"] = median(traverse);
  r["triangle_cull_ms"] = median(triangles);
  r["raster_ms"] = median(raster);    // the compute rasterizers: small triangles, then patches
  r["draw_ms"] = median(draw);        // the render pass: hardware draws
  r["resolve_ms"] = median(resolve);  // the compute rasterizers' pixels shaded
  r["pyramid_ms"] = median(pyramid);  // occlusion culling's depth pyramid
  r["frame_ms"] = median(frame);
  r["frame_max_ms"] = *std::max_element(frame.begin(), frame.end());
  // The mean too: Auto's probes are a frame or two in kOcclusionProbePeriod, which a median leaves out.
  r["frame_mean_ms"] = std::accumulate(frame.begin(), frame.end(), 0.0) / double(frame.size());
  r["occlusion_setting"] = occlusionName(occlusion);
  r["clusters_median"] = median(clusters);  // drawn (a fly-through's vary; the counters are its last frame's)
  addFrameCounters(r, f, renderer, vk);
  r["pixels_covered"] = covered;
  r["triangles_per_covered_pixel"] = covered ? double(f.trianglesDrawn) / double(covered) : 0.0;
  // The pixels the patches cover, and the tessellator's triangles a patch pixel.
  r["patch_pixels"] = patchCovered;
  r["patch_triangles_per_patch_pixel"] =
      patchCovered && f.patchTriangles > 0 ? double(f.patchTriangles) / double(patchCovered) : 0.0;
  r["frames"] = count;
  // The first pose as `vgeo render --camera` takes it, to look at what was measured.
  r["camera_option"] = cameraOption(poses[0]);
  r["commit"] = VGEO_COMMIT;
  std::fprintf(
      stderr,
      "%7zu instances %4ux%-4u %-9s tc %-3s patches %-3s %-8s occlusion %-4s: cull %.3f  traversal %.3f  "
      "triangles %.3f  raster %.3f  draw %.3f  resolve %.3f  pyramid %.3f  frame %.3f ms (mean %.3f; %.0f clusters, %u "
      "early; %u of %u triangles, %u of %u patches in compute)\n",
      scene.data.instances.size(), width, height, poses.size() > 1 ? "path" : "", triangleCull ? "on" : "off",
      patches ? "on" : "off", variant.raster.c_str(), occlusionName(occlusion), median(cull), median(traverse),
      median(triangles), median(raster), median(draw), median(resolve), median(pyramid), median(frame),
      r["frame_mean_ms"].get<double>(), median(clusters), f.counters.drawBase, f.softwareTriangles, f.trianglesDrawn,
      f.softwarePatches, f.patchesDrawn);
  return r;
}

void runBenchFrame(const FrameBenchArgs& a) {
  traversalNamed("--traversal", a.traversal);  // checked before any work
  const BenchLayout layout = benchLayoutNamed(a.layout);
  std::vector<Occlusion> occlusions;
  for (const std::string& o : parseList<std::string>(a.occlusion))
    occlusions.push_back(occlusionNamed("--occlusion", o));
  VulkanContext vk({a.device, false});
  nlohmann::ordered_json records = nlohmann::json::array();
  for (uint32_t grid : parseList<uint32_t>(a.grids)) {
    // A grid copies the whole scene; the other layouts place grid x grid instances of its first geometry.
    RenderScene scene = layout == BenchLayout::Grid ? loadRenderScene(a.input, grid)
                                                    : makeBenchScene(loadRenderScene(a.input), grid * grid, layout, 7);
    for (const std::string& size : parseList<std::string>(a.sizes)) {
      uint32_t width, height;
      if (!parseSize(size, width, height)) throw std::runtime_error("--sizes: expected WxH items");
      GpuRenderer renderer(vk, scene, width, height);
      auto path = cameraPath(scene, a.fov);
      for (const std::string& cameraName : parseList<std::string>(a.cameras)) {
        std::vector<Camera> poses;
        if (cameraName == "flythrough") {
          poses = flyThrough(path, a.pathFrames);
        } else {
          auto camera = std::find_if(path.begin(), path.end(), [&](const auto& p) { return p.first == cameraName; });
          if (camera == path.end()) throw std::runtime_error("--cameras: unknown camera '" + cameraName + "'");
          poses.push_back(camera->second);
        }
        std::vector<Variant> variants;
        for (const std::string& raster : parseList<std::string>(a.rasters)) {
          rasterNamed("--rasters", raster);
          variants.push_back({true, true, raster});
          variants.push_back({true, false, raster});
        }
        variants.push_back({false, false, "hardware"});
        for (const Variant& variant : variants)
          for (Occlusion occlusion : occlusions) {
            nlohmann::ordered_json r = measureFrames(a, renderer, vk, scene, poses, variant, occlusion);
            r["camera"] = cameraName;
            records.push_back(r);
          }
      }
    }
  }
  writeJson(a.output, records, 1);
}

}  // namespace

void addBenchFrameCommand(CLI::App& bench, int& exitCode) {
  auto* cmd =
      bench.add_subcommand("frame", "Whole frames split into instance culling, traversal, triangle culling and draw");
  auto a = std::make_shared<FrameBenchArgs>();
  cmd->add_option("input", a->input, ".vgeo or scene file")->required();
  cmd->add_option("-o,--output", a->output, "JSON records")->required();
  cmd->add_option("--grids", a->grids, "N for N x N copies of the input (the main job's default scene is 32)")
      ->capture_default_str();
  cmd->add_option("--sizes", a->sizes, "Viewports WxH")->capture_default_str();
  cmd->add_option("--cameras", a->cameras,
                  "far, corner (the default camera), inside, closeup, surface, away, ground, above, flythrough (from "
                  "ground to above in --path-frames frames)")
      ->capture_default_str();
  cmd->add_option("--layout", a->layout,
                  "grid (N x N copies of the input), forest (N x N instances of its first geometry packed in rows)")
      ->check(CLI::IsMember({"grid", "forest"}))
      ->capture_default_str();
  cmd->add_option("--occlusion", a->occlusion, "Occlusion culling auto, on and/or off (a record each)")
      ->capture_default_str();
  cmd->add_option("--path-frames", a->pathFrames, "Frames of the fly-through")
      ->capture_default_str()
      ->check(CLI::Range(2u, 100000u));
  addTraversalOption(cmd, a->traversal);
  cmd->add_option("--tau", a->tau, "Allowed projected error, pixels")->capture_default_str();
  cmd->add_option("--frames", a->frames, "Measured frames per record (median)")->capture_default_str();
  cmd->add_option("--rasters", a->rasters,
                  "Rasterizers to compare (auto, hardware, software), each with and without patches")
      ->capture_default_str();
  addPackedCullOption(cmd, a->packedCullBelow);
  addDeviceOption(cmd, a->device);
  cmd->callback([a, &exitCode] {
    runBenchFrame(*a);
    exitCode = 0;
  });
}

}  // namespace vgeo
