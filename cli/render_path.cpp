// render_path.cpp: `vgeo render INPUT --path SCRIPT -o DIR`: the viewer's script (docs/viewer.md) played
// without a window, a PNG a frame (DIR/frame_00000.png on): a turntable or a fly-through for people
// without a display. The events change the same state the viewer's do (viewer/view_state.cpp), so the
// frames are the viewer's screenshots of the same frames.
#include <cstdio>

#include "../renderer/image.h"
#include "../viewer/view_state.h"
#include "commands.h"
#include "options.h"
#include "render_path.h"

namespace vgeo {

int renderPath(const std::vector<ViewEvent>& script, const std::string& folder, VulkanContext& vk,
               const RenderScene& scene, std::optional<GpuRenderer>& renderer, const FrameSettings& initial,
               const Camera& camera, const std::optional<Camera>& frozen) {
  ViewState s;
  s.fov = camera.fovYDegrees;
  s.home = camera;
  s.camera = FlyCamera::from(camera, scene.bounds.w * 0.5f);
  s.frame = initial;
  s.frozen = frozen.has_value();
  if (frozen) s.frozenCamera = *frozen;
  ScriptPlayer player{script};
  uint32_t written = 0;
  for (uint32_t frame = 0;; frame++) {
    uint32_t width = 0, height = 0;
    playEvents(player, frame, s, width, height);
    if (s.quit) break;
    if (width && (width != renderer->width() || height != renderer->height())) {
      renderer.reset();
      renderer.emplace(vk, scene, width, height);
    }
    FrameSettings settings = frameSettings(s, scene, renderer->width(), renderer->height());
    settings.readImage = true;
    FrameResult result = renderer->renderFrame(settings);
    for (int i = 0; i < 12 && !result.complete; i++) result = renderer->renderFrame(settings);  // lists grown
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%05u.png", frame);
    writePng(folder + name, renderer->width(), renderer->height(), result.rgba);
    written++;
    if (!s.screenshot.empty()) writePng(s.screenshot, renderer->width(), renderer->height(), result.rgba);
    s.screenshot.clear();
    s.windowShot.clear();  // no window here
    if (player.done()) break;
  }
  std::printf("%s: %u frames (frame_00000.png on) on %s\n", folder.c_str(), written, vk.deviceName().c_str());
  if (vk.validationMessages() > 0) {
    std::fprintf(stderr, "validation: %u messages\n", vk.validationMessages());
    return kExitValidation;
  }
  return kExitOk;
}

}  // namespace vgeo
