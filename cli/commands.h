// commands.h: each subcommand of `vgeo` registers itself on the CLI11 app.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "../common/atomic_file.h"
#include "../renderer/gpu_renderer.h"

namespace vgeo {

// "WxH" with both in 1..16384, digits only, nothing after (sscanf's %u wrapped 4294967616 to 320).
inline bool parseSize(const std::string& text, uint32_t& width, uint32_t& height) {
  const size_t x = text.find('x');
  auto number = [](const std::string& digits, uint32_t& out) {
    if (digits.empty() || digits.size() > 5 || digits.find_first_not_of("0123456789") != std::string::npos)
      return false;
    out = uint32_t(std::stoul(digits));
    return out > 0 && out <= 16384;
  };
  return x != std::string::npos && number(text.substr(0, x), width) && number(text.substr(x + 1), height);
}

// Writes JSON (stats, benchmark records) to `path`, atomically; throws OutputError("path: cause").
inline void writeJson(const std::string& path, const nlohmann::ordered_json& j, int indent) {
  writeFileAtomically(path, j.dump(indent) + "\n");
}

// --instance-culling auto|pass|traversal (render and bench cut), for FrameSettings::instanceCulling.
inline void addInstanceCullingOption(CLI::App* cmd, std::string& name) {
  cmd->add_option(
         "--instance-culling", name,
         "Persistent traversal: cull the instances in a pass of their own, or first thing in the traversal's dispatch "
         "(auto: the traversal on GPUs in scenes of up to 3 instances a worker)")
      ->check(CLI::IsMember({"auto", "pass", "traversal"}))
      ->capture_default_str();
}
inline void addPackedCullOption(CLI::App* cmd, uint32_t& below) {
  cmd->add_option("--packed-cull-below", below,
                  "Triangle culling takes " + std::to_string(VGEO_PACKED_CULL_ENTRIES) +
                      " listed clusters a workgroup when they average fewer triangles than this (0: never)")
      ->check(CLI::Range(0u, 1u << 20))
      ->capture_default_str();
}
inline InstanceCulling instanceCullingNamed(const std::string& name) {
  return name == "pass"        ? InstanceCulling::Pass
         : name == "traversal" ? InstanceCulling::InTraversal
                               : InstanceCulling::Auto;
}

// --raster auto|hardware|software (render), the names of FrameSettings::raster.
inline constexpr std::pair<const char*, Raster> kRasters[] = {
    {"auto", Raster::Auto}, {"hardware", Raster::Hardware}, {"software", Raster::Software}};
inline Raster rasterNamed(const std::string& option, const std::string& name) {
  for (const auto& [n, r] : kRasters)
    if (name == n) return r;
  throw std::runtime_error(option + ": unknown rasterizer '" + name + "' (auto, hardware or software)");
}

// --occlusion auto|on|off (render, and lists of them in bench frame), the names of FrameSettings::occlusion.
inline constexpr std::pair<const char*, Occlusion> kOcclusions[] = {
    {"auto", Occlusion::Auto}, {"on", Occlusion::On}, {"off", Occlusion::Off}};
inline Occlusion occlusionNamed(const std::string& option, const std::string& name) {
  for (const auto& [n, o] : kOcclusions)
    if (name == n) return o;
  throw std::runtime_error(option + ": unknown occlusion culling '" + name + "' (auto, on or off)");
}
inline const char* occlusionName(Occlusion occlusion) {
  for (const auto& [n, o] : kOcclusions)
    if (o == occlusion) return n;
  return "?";
}

// The scene and view options `render` and `view` share: --fov, --tau, --mode, --grid, --layout.
void addSceneViewOptions(CLI::App* cmd, float& fov, float& tau, std::string& mode, uint32_t& grid, std::string& layout);
// The scene those options name: --grid copies of the input, or a forest of N x N instances of its first
// geometry.
RenderScene loadLaidOutScene(const std::string& input, uint32_t grid, const std::string& layout);

// --traversal persistent|levels|flat (render and bench frame) and its value; bench cut lists several.
inline constexpr Traversal kTraversals[] = {Traversal::Persistent, Traversal::Levels, Traversal::Flat};
inline void addTraversalOption(CLI::App* cmd, std::string& name) {
  std::vector<std::string> names;
  for (Traversal t : kTraversals) names.push_back(traversalName(t));
  cmd->add_option("--traversal", name, "Cut selection")->capture_default_str()->check(CLI::IsMember(names));
}
// Throws std::runtime_error("OPTION: unknown traversal 'NAME'") for a name traversalName gives none.
inline Traversal traversalNamed(const std::string& option, const std::string& name) {
  for (Traversal t : kTraversals)
    if (name == traversalName(t)) return t;
  throw std::runtime_error(option + ": unknown traversal '" + name + "'");
}

// --device NAME (every command that opens a Vulkan device).
inline void addDeviceOption(CLI::App* cmd, std::string& name) {
  cmd->add_option("--device", name, "Use the first Vulkan device whose name contains this");
}

// What one GPU frame reports, for `render --stats` and the bench records: the device, how it was timed
// and the counters of the cut and the draw (docs/design.md names each).
void addFrameCounters(nlohmann::ordered_json& record, const FrameResult& frame, const GpuRenderer& renderer,
                      const VulkanContext& vk);

void addBuildCommand(CLI::App& app, int& exitCode);
void addCheckCommand(CLI::App& app, int& exitCode);
void addRenderCommand(CLI::App& app, int& exitCode);
void addViewCommand(CLI::App& app, int& exitCode);
void addBenchCommand(CLI::App& app, int& exitCode);

}  // namespace vgeo
