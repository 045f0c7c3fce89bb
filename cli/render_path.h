// render_path.h: `vgeo render --path SCRIPT -o DIR` (render_path.cpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "../renderer/gpu_renderer.h"
#include "../viewer/viewer.h"

namespace vgeo {

// Plays `script` from `camera` (and the cut frozen at `frozen`) with `initial`'s settings, writing each
// frame to folder/frame_NNNNN.png; a resize remakes `renderer`. Returns the exit code.
int renderPath(const std::vector<ViewEvent>& script, const std::string& folder, VulkanContext& vk,
               const RenderScene& scene, std::optional<GpuRenderer>& renderer, const FrameSettings& initial,
               const Camera& camera, const std::optional<Camera>& frozen);

}  // namespace vgeo
