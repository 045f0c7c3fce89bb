// viewer.h: `vgeo view`: a window on the renderer (viewer.cpp): the same frames as `vgeo render`, copied
// to a swapchain with a panel over them; a fly camera, the frame's settings and a frozen cut changed
// live, and scripted runs (docs/viewer.md) for tests, demos and bug reports.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "../renderer/camera.h"
#include "../renderer/gpu_renderer.h"
#include "../renderer/scene.h"

namespace vgeo {

// One event of a script (docs/viewer.md), applied at the start of frame `frame`.
struct ViewEvent {
  enum class Kind {
    Camera,
    Path,
    Mode,
    Tau,
    Occlusion,
    Patches,
    TriangleCull,
    Freeze,
    Resize,
    Minimise,
    Screenshot,
    WindowShot,
    Key,
    Quit
  };
  uint32_t frame = 0;
  Kind kind = Kind::Quit;
  Camera camera;        // Camera, Path (the pose to reach)
  uint32_t frames = 0;  // Path: over how many frames
  uint32_t mode = 0;    // Mode (VGEO_MODE_*)
  float value = 0.0f;   // Tau; Minimise: seconds
  Occlusion occlusion = Occlusion::Auto;
  bool on = false;                 // Patches, TriangleCull, Freeze
  uint32_t width = 0, height = 0;  // Resize
  std::string text;                // Screenshot, WindowShot: the PNG's path; Key: the key's name
};

struct ViewerOptions {
  std::string title;  // the input's name
  Camera camera;      // the first camera
  uint32_t width = 1280, height = 720;
  std::string device;
  bool validate = false, vsync = true;
  float tau = 1.0f;
  uint32_t mode = VGEO_MODE_LIT;
  std::vector<ViewEvent> script;  // in frame order
};

// The display is missing or refuses a window: one line for the user, who can render to PNG instead.
struct NoDisplayError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Runs the viewer until the window closes or the script quits; the validation layer's message count
// (with `validate`) is returned.
uint32_t runViewer(const RenderScene& scene, const ViewerOptions& options);

}  // namespace vgeo
