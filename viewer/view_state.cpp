// view_state.cpp: what changes the viewer's state between frames, apart from the window: the keys
// (pressKey), a script's events (playEvents) and the frame's settings made of the state. `vgeo render
// --path` plays scripts with the same code, so its PNGs are the viewer's screenshots.
#include "view_state.h"

#include <algorithm>
#include <cstdio>
#include <ctime>

#include "../renderer/debug_modes.h"

namespace vgeo {

namespace {

void cycleMode(ViewState& s) {
  const size_t count = std::size(kDebugModes);
  for (size_t i = 0; i < count; i++)
    if (kDebugModes[i].mode == s.frame.mode) {
      s.frame.mode = kDebugModes[(i + 1) % count].mode;
      return;
    }
  s.frame.mode = VGEO_MODE_LIT;
}

void printCamera(const ViewState& s) {
  const Camera c = s.camera.camera(s.fov);
  std::printf("--camera %s", cameraOption(c).c_str());
  if (s.headlight) {
    const glm::vec3 l = headlight(s.camera);
    std::printf(" --light %.9g,%.9g,%.9g", l.x, l.y, l.z);
  }
  std::printf("\n");
  std::fflush(stdout);
}

}  // namespace

bool pressKey(ViewState& s, const std::string& key) {
  if (key == "F") {
    s.frozen = !s.frozen;
    s.frozenCamera = s.camera.camera(s.fov);
  } else if (key == "M") {
    cycleMode(s);
  } else if (key == "P") {
    s.frame.patches = !s.frame.patches;
  } else if (key == "T") {
    s.frame.triangleCull = !s.frame.triangleCull;
  } else if (key == "O") {
    s.frame.occlusion = s.frame.occlusion == Occlusion::Auto ? Occlusion::On
                        : s.frame.occlusion == Occlusion::On ? Occlusion::Off
                                                             : Occlusion::Auto;
  } else if (key == "Tab") {
    s.panel = !s.panel;
  } else if (key == "L") {
    s.headlight = !s.headlight;
  } else if (key == "H") {
    s.camera = FlyCamera::from(s.home, s.camera.speed);
  } else if (key == "C") {
    printCamera(s);
  } else if (key == "+") {
    s.frame.tau *= 1.25f;
  } else if (key == "-") {
    s.frame.tau /= 1.25f;
  } else if (key == "F12") {  // a screenshot named by the time
    char name[64];
    std::snprintf(name, sizeof name, "vgeo-view-%ld.png", long(std::time(nullptr)));
    s.screenshot = name;
  } else if (key == "Escape") {
    s.quit = true;
  } else {
    return false;
  }
  return true;
}

// The frame's settings, as `vgeo render` would have them.
FrameSettings frameSettings(const ViewState& s, const RenderScene& scene, uint32_t width, uint32_t height) {
  FrameSettings f = s.frame;
  f.drawView = makeView(s.camera.camera(s.fov), width, height, scene.bounds);
  f.cullView = s.frozen ? makeView(s.frozenCamera, width, height, scene.bounds) : f.drawView;
  f.readImage = !s.screenshot.empty();
  if (s.headlight) f.light = headlight(s.camera);
  return f;
}

// Applies the script's events of `frame` to the state; a resize is returned in width, height (0: none).
void playEvents(ScriptPlayer& p, uint32_t frame, ViewState& s, uint32_t& width, uint32_t& height) {
  width = height = 0;
  for (; p.next < p.events.size() && p.events[p.next].frame <= frame; p.next++) {
    const ViewEvent& e = p.events[p.next];
    switch (e.kind) {
      case ViewEvent::Kind::Camera:
        s.camera = FlyCamera::from(e.camera, s.camera.speed);
        p.pathFrames = 0;
        break;
      case ViewEvent::Kind::Path:
        p.pathFrom = s.camera.camera(s.fov);
        p.pathTo = e.camera;
        p.pathStart = frame;
        p.pathFrames = std::max(e.frames, 1u);
        break;
      case ViewEvent::Kind::Mode:
        s.frame.mode = e.mode;
        break;
      case ViewEvent::Kind::Tau:
        s.frame.tau = e.value;
        break;
      case ViewEvent::Kind::Occlusion:
        s.frame.occlusion = e.occlusion;
        break;
      case ViewEvent::Kind::Patches:
        s.frame.patches = e.on;
        break;
      case ViewEvent::Kind::TriangleCull:
        s.frame.triangleCull = e.on;
        break;
      case ViewEvent::Kind::Freeze:
        s.frozen = e.on;
        s.frozenCamera = s.camera.camera(s.fov);
        break;
      case ViewEvent::Kind::Resize:
        width = e.width;
        height = e.height;
        break;
      case ViewEvent::Kind::Minimise:
        s.minimiseSeconds = e.value;
        break;
      case ViewEvent::Kind::Screenshot:
        s.screenshot = e.text;
        break;
      case ViewEvent::Kind::WindowShot:
        s.windowShot = e.text;
        break;
      case ViewEvent::Kind::Key:
        pressKey(s, e.text);
        break;
      case ViewEvent::Kind::Quit:
        s.quit = true;
        break;
    }
  }
  if (p.pathFrames) {  // along the path: eye and target each on a straight line
    const float t = std::min(float(frame - p.pathStart + 1) / float(p.pathFrames), 1.0f);
    Camera c = p.pathFrom;
    c.eye = glm::mix(p.pathFrom.eye, p.pathTo.eye, t);
    c.target = glm::mix(p.pathFrom.target, p.pathTo.target, t);
    s.camera = FlyCamera::from(c, s.camera.speed);
    if (t >= 1.0f) {  // the pose itself at the end, not a rounding of it
      s.camera = FlyCamera::from(p.pathTo, s.camera.speed);
      p.pathFrames = 0;
    }
  }
}

}  // namespace vgeo
