// view_state.h: what the viewer's keys, panel and script change between frames (viewer.cpp, panel.cpp).
#pragma once

#include <string>

#include "../renderer/gpu_renderer.h"
#include "fly_camera.h"

namespace vgeo {

struct ViewState {
  FlyCamera camera;
  Camera home;  // the first camera: the Home key goes back to it
  float fov = 60.0f;
  uint32_t mode = VGEO_MODE_LIT;
  float tau = 1.0f;
  Occlusion occlusion = Occlusion::Auto;
  Traversal traversal = Traversal::Persistent;
  InstanceCulling instanceCulling = InstanceCulling::Auto;
  bool patches = true, triangleCull = true;
  bool headlight = false;  // light from the camera (FrameSettings::light), else the fixed light
  bool frozen = false;     // the cut and its culling stay with frozenCamera
  Camera frozenCamera;
  std::string screenshot;  // a path: the next frame's picture is written there
  std::string windowShot;  // a path: the next frame's window, panel and all
  bool quit = false;
};

// The headlight's direction: from the eye, a little from above.
inline glm::vec3 headlight(const FlyCamera& c) { return -c.forward() + glm::vec3(0.0f, 0.3f, 0.0f); }

// What the panel shows of the last frame.
struct ViewStats {
  FrameResult frame;
  double frameMs = 0.0;  // the viewer's whole frame on the host: render, copy, panel, present
  uint32_t width = 0, height = 0;
  uint32_t lodLevels = 0;  // the lod view's scale (RenderScene::maxLevels)
  std::string device, lastScreenshot;
};

// The keys pressKey knows (the panel lists them; scripts name them the same way).
inline constexpr const char* kViewerKeys[] = {"F", "M", "P", "T", "O", "L", "H", "C", "+", "-", "F12", "Escape"};
inline bool isViewerKey(const std::string& key) {
  for (const char* k : kViewerKeys)
    if (key == k) return true;
  return false;
}

// The panel (panel.cpp): the stats, the settings as controls, the keys and the view's legend.
void drawPanel(ViewState& state, const ViewStats& stats);
// The frozen camera's frustum as lines over the picture drawn from `draw` (to farDistance from its eye).
void drawFrozenFrustum(const View& frozen, const View& draw, float farDistance);
// A key press by name (the panel's key list; scripts send the same names): true when it is one.
bool pressKey(ViewState& state, const std::string& key);

}  // namespace vgeo
