// view_state.h: what the viewer's keys, panel and script change between frames (viewer.cpp, panel.cpp).
#pragma once

#include <string>
#include <vector>

#include "../renderer/gpu_renderer.h"
#include "viewer.h"
#include "fly_camera.h"

namespace vgeo {

struct ViewState {
  FlyCamera camera;
  Camera home;  // the first camera: the Home key goes back to it
  float fov = 60.0f;
  // The frame's settings but the views and the image read-back (frameSettings makes those): view, tau,
  // occlusion, traversal, culling, patches, the fixed light, the pyramid view's level.
  FrameSettings frame;
  bool panel = true;       // the panel is shown (Tab)
  bool headlight = false;  // light from the camera, else frame.light
  bool frozen = false;     // the cut and its culling stay with frozenCamera
  Camera frozenCamera;
  std::string screenshot;        // a path: the next frame's picture is written there
  std::string windowShot;        // a path: the next frame's window, panel and all
  float minimiseSeconds = 0.0f;  // a script's minimise: the window is minimised for this long
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
inline constexpr const char* kViewerKeys[] = {"F", "M", "P", "T", "O", "L", "H", "C", "+", "-", "F12", "Tab", "Escape"};
inline bool isViewerKey(const std::string& key) {
  for (const char* k : kViewerKeys)
    if (key == k) return true;
  return false;
}

// A script's progress (docs/viewer.md): the next event, and a camera path under way.
struct ScriptPlayer {
  const std::vector<ViewEvent>& events;
  size_t next = 0;
  Camera pathFrom, pathTo;
  uint32_t pathStart = 0, pathFrames = 0;
  bool done() const { return next >= events.size() && pathFrames == 0; }
};
// Applies the script's events of `frame` (and the path's pose) to the state; a resize is returned in
// width, height (0: none).
void playEvents(ScriptPlayer& player, uint32_t frame, ViewState& state, uint32_t& width, uint32_t& height);
// The frame's settings made of the state, as `vgeo render` would have them for that camera.
FrameSettings frameSettings(const ViewState& state, const RenderScene& scene, uint32_t width, uint32_t height);

// The panel (panel.cpp): the stats, the settings as controls, the keys and the view's legend.
void drawPanel(ViewState& state, const ViewStats& stats);
// The frozen camera's frustum as lines over the picture drawn from `draw` (to farDistance from its eye).
void drawFrozenFrustum(const View& frozen, const View& draw, float farDistance);
// A key press by name (the panel's key list; scripts send the same names): true when it is one.
bool pressKey(ViewState& state, const std::string& key);

}  // namespace vgeo
