// debug_modes.h: the views a frame can be shaded in (FrameSettings::mode, shaders/shade.glsl), their
// names on the command line and in the viewer, and what their colours mean.
#pragma once

#include <cstdint>
#include <string>

#include "../shaders/shaderio.h"

namespace vgeo {

struct DebugMode {
  const char* name;
  uint32_t mode;  // VGEO_MODE_*
  const char* legend;
};

inline constexpr DebugMode kDebugModes[] = {
    {"lit", VGEO_MODE_LIT, "the surface lit by a fixed light from above, the right and the front (or the headlight)"},
    {"normal", VGEO_MODE_NORMAL, "the world normal as colour (x red, y green, z blue)"},
    {"cluster", VGEO_MODE_CLUSTER, "a colour a cluster"},
    {"group", VGEO_MODE_GROUP, "a colour a simplification group"},
    {"lod", VGEO_MODE_LOD, "the DAG level: blue the leaves, red the roots (the scene's most levels)"},
    {"triangle", VGEO_MODE_TRIANGLE, "a colour a triangle"},
    {"instance", VGEO_MODE_INSTANCE, "a colour an instance"},
    {"error", VGEO_MODE_ERROR, "the cluster's projected error against tau: blue 0, red at tau"},
    {"wire", VGEO_MODE_WIRE, "lit, with every triangle's edges dark"},
    {"overdraw", VGEO_MODE_OVERDRAW, "layers drawn a pixel: brighter is more"},
    {"frozen-diff", VGEO_MODE_FROZEN_DIFF,
     "a frozen cut against the live camera's: green the same cluster, red it would pick finer, blue coarser"},
    {"patch", VGEO_MODE_PATCH,
     "leaves drawn as patches by their largest tessellation factor: blue 1, green 8, red 64; triangles grey"},
    {"pyramid", VGEO_MODE_PYRAMID,
     "the depth pyramid occlusion culling tests against, one level: the farthest depth drawn under each texel, "
     "nearer brighter; black where part of it was not drawn (it hides nothing there)"},
};

// The mode named `name`, or nullptr.
inline const DebugMode* debugModeNamed(const std::string& name) {
  for (const DebugMode& m : kDebugModes)
    if (name == m.name) return &m;
  return nullptr;
}

}  // namespace vgeo
