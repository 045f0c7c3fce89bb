// view_command.cpp: `vgeo view INPUT`: the viewer (viewer/viewer.h) on the same scene, camera and frame
// settings as `vgeo render`; `--script FILE` plays timed events (docs/viewer.md).
#include <CLI/CLI.hpp>
#include <cstdio>

#include "../renderer/debug_modes.h"
#include "../viewer/viewer.h"
#include "commands.h"
#include "options.h"
#include "view_script.h"

namespace vgeo {
namespace {

struct ViewArgs {
  std::string input, camera, size = "1280x720", device, script, mode = "lit", layout = "grid";
  float fov = 60.0f, tau = 1.0f;
  uint32_t grid = 1;
  bool validate = false, noVsync = false;
};

int runView(const ViewArgs& a) {
  ViewerOptions o;
  if (!parseSize(a.size, o.width, o.height))
    throw UsageError("--size", "expected WxH with both in 1..16384, e.g. 1280x720 (got '" + a.size + "')");
  std::optional<Camera> camera;
  if (!a.camera.empty()) camera = parseCameraOption("--camera", a.camera, a.fov);
  if (!a.script.empty()) o.script = readViewScript(a.script, a.fov, {a.input, a.script});
  RenderScene scene = loadLaidOutScene(a.input, a.grid, a.layout);
  if (!camera) camera = sceneCamera(scene, a.fov, float(o.width) / float(o.height));
  camera->fovYDegrees = a.fov;
  o.camera = *camera;
  o.title = a.input;
  o.device = a.device;
  o.validate = a.validate;
  o.vsync = !a.noVsync;
  o.tau = a.tau;
  o.mode = debugModeNamed(a.mode)->mode;
  const uint32_t messages = runViewer(scene, o);
  if (messages > 0) {
    std::fprintf(stderr, "validation: %u messages\n", messages);
    return kExitValidation;
  }
  return kExitOk;
}

}  // namespace

void addViewCommand(CLI::App& app, int& exitCode) {
  auto* cmd = app.add_subcommand("view", "Fly through a .vgeo or a scene file in a window (the renderer of `render`)");
  auto a = std::make_shared<ViewArgs>();
  cmd->add_option("input", a->input, ".vgeo file or scene file (.json)")->required();
  cmd->add_option("--camera", a->camera, "eye_x,eye_y,eye_z,target_x,target_y,target_z (default: frames the scene)");
  cmd->add_option("--size", a->size, "Window size WxH")->capture_default_str();
  addSceneViewOptions(cmd, a->fov, a->tau, a->mode, a->grid, a->layout);
  cmd->add_option("--script", a->script, "Timed events to play (docs/viewer.md): camera, path, settings, screenshots");
  addDeviceOption(cmd, a->device);
  cmd->add_flag("--validate", a->validate,
                "Khronos validation layer with synchronization validation (exit 3 on any message)");
  cmd->add_flag("--no-vsync", a->noVsync, "Present as fast as frames come (default: at the display's rate)");
  cmd->callback([a, &exitCode] { exitCode = runView(*a); });
}

}  // namespace vgeo
