// bench.h: what the `vgeo bench` subcommands share (bench_command.cpp, bench_frame.cpp, bench_build.cpp).
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../renderer/camera.h"
#include "../renderer/scene.h"

#include "vgeo_commit.h"  // generated at build time (cmake/commit.cmake)
#ifndef VGEO_COMMIT
#define VGEO_COMMIT "unknown"
#endif

namespace vgeo {

// "a,b,c" -> {a, b, c}; throws std::runtime_error on an item that does not parse as T.
template <class T>
std::vector<T> parseList(const std::string& text) {
  std::vector<T> out;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) {
    std::stringstream v(item);
    T x;
    if (!(v >> x)) throw std::runtime_error("bad list item '" + item + "'");
    out.push_back(x);
  }
  return out;
}

// The benchmark camera path over a scene, by name: far (the whole scene small), corner (the default
// camera: over its near corner), inside (low inside it), closeup (one instance), surface (one instance
// from nearer than its size: most leaves drawn as patches), away (inside, looking out of it).
std::vector<std::pair<std::string, Camera>> cameraPath(const RenderScene& scene, float fov);

// Median of v (the upper one of an even count); 0 for none.
double median(std::vector<double> v);

// A summary of one frame's persistent-traversal worker profile (FrameResult::workerProfile of `workgroups`
// workgroups): iterations, polls, the span from the first start to the last exit, when the first item
// was taken and the last finished, and median claim / take / rounds times of the iterations that took
// items, in device-clock ticks (worker_profile.cpp).
nlohmann::ordered_json summarizeWorkerProfile(const std::vector<uint32_t>& words, uint32_t workgroups);

class VulkanContext;
// DAG quality as numbers (cut_quality.cpp): from the views of qualityViews (the framing camera from the
// front, right, back and left, and four times as far), the cut at `tau` of `scene` (one geometry):
// triangles listed and drawn per covered pixel, and the share of pixels whose coverage or normal differs
// from the leaves' picture; the totals and a record per view.
std::vector<std::pair<std::string, Camera>> qualityViews(const RenderScene& scene, uint32_t width, uint32_t height);
nlohmann::ordered_json measureCutQuality(VulkanContext& vk, const RenderScene& scene, uint32_t width, uint32_t height,
                                         float tau);

void addBenchFrameCommand(CLI::App& bench, int& exitCode);
void addBenchBuildCommand(CLI::App& bench, int& exitCode);

}  // namespace vgeo
