// view_script.cpp: reads a viewer script (docs/viewer.md): "FRAME COMMAND [ARGUMENTS]" a line, '#'
// starting a comment, frames never decreasing. The arguments are those of the command-line options of
// the same name (a camera as --camera takes it, a mode as --mode, a size as --size).
#include "view_script.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "../common/input_error.h"
#include "../renderer/debug_modes.h"
#include "../viewer/view_state.h"
#include "commands.h"
#include "options.h"

namespace vgeo {

namespace {

bool onOff(const std::string& word, bool& on) {
  on = word == "on";
  return word == "on" || word == "off";
}

}  // namespace

std::vector<ViewEvent> readViewScript(const std::string& path, float fovYDegrees,
                                      const std::vector<std::string>& inputs) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot be read");
  std::vector<ViewEvent> events;
  std::string line;
  for (uint32_t number = 1; std::getline(in, line); number++) {
    const std::string where = "line " + std::to_string(number);
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::string frameText, command;
    if (!(words >> frameText)) continue;  // empty or a comment
    ViewEvent e;
    try {
      size_t used = 0;
      const long long frame = std::stoll(frameText, &used);
      if (used != frameText.size() || frame < 0 || frame > (1ll << 31)) throw std::invalid_argument(frameText);
      e.frame = uint32_t(frame);
    } catch (const std::exception&) {
      throw InputError(path, where + ": a line starts with a frame number (got '" + frameText + "')");
    }
    if (!events.empty() && e.frame < events.back().frame)
      throw InputError(path, where + ": frame " + frameText + " comes before the line above's");
    if (!(words >> command)) throw InputError(path, where + ": a command follows the frame number");
    std::string arg, extra;
    words >> arg;
    auto bad = [&](const std::string& expected) {
      return InputError(path, where + ": " + command + " takes " + expected + " (got '" + arg + "')");
    };
    try {
      if (command == "camera") {
        e.kind = ViewEvent::Kind::Camera;
        e.camera = parseCameraOption(where + ": camera", arg, fovYDegrees);
      } else if (command == "path") {  // path FRAMES POSE
        e.kind = ViewEvent::Kind::Path;
        std::string pose;
        words >> pose;
        e.frames = uint32_t(std::stoul(arg));
        if (e.frames == 0 || e.frames > 1000000) throw bad("a frame count of 1 to 1000000 and a camera");
        e.camera = parseCameraOption(where + ": path", pose, fovYDegrees);
      } else if (command == "mode") {
        e.kind = ViewEvent::Kind::Mode;
        const DebugMode* mode = debugModeNamed(arg);
        if (!mode) throw bad("a view's name, as --mode");
        e.mode = mode->mode;
      } else if (command == "tau") {
        e.kind = ViewEvent::Kind::Tau;
        e.value = std::stof(arg);
        if (!(e.value > 0.0f) || !std::isfinite(e.value)) throw bad("a positive number of pixels");
      } else if (command == "occlusion") {
        e.kind = ViewEvent::Kind::Occlusion;
        e.occlusion = occlusionNamed(where + ": occlusion", arg);
      } else if (command == "patches" || command == "triangle-cull" || command == "freeze") {
        e.kind = command == "patches"         ? ViewEvent::Kind::Patches
                 : command == "triangle-cull" ? ViewEvent::Kind::TriangleCull
                                              : ViewEvent::Kind::Freeze;
        if (!onOff(arg, e.on)) throw bad("on or off");
      } else if (command == "resize") {
        e.kind = ViewEvent::Kind::Resize;
        if (!parseSize(arg, e.width, e.height)) throw bad("a size WxH");
      } else if (command == "minimise") {
        e.kind = ViewEvent::Kind::Minimise;
        e.value = std::stof(arg);
        if (!(e.value > 0.0f) || e.value > 3600.0f) throw bad("seconds, more than 0 and at most 3600");
      } else if (command == "screenshot" || command == "window-screenshot") {
        e.kind = command == "screenshot" ? ViewEvent::Kind::Screenshot : ViewEvent::Kind::WindowShot;
        e.text = arg;
        checkOutputPath(path + ": " + where + ": " + command, arg, inputs, ".png");
      } else if (command == "key") {
        e.kind = ViewEvent::Kind::Key;
        e.text = arg;
        if (!isViewerKey(arg)) throw bad("one of the viewer's keys (F M P T O L H C + - F12 Tab Escape)");
      } else if (command == "quit") {
        e.kind = ViewEvent::Kind::Quit;
        if (!arg.empty())
          throw InputError(path, where + ": quit takes no more than its arguments ('" + arg + "' left over)");
      } else {
        throw InputError(path, where + ": unknown command '" + command +
                                   "' (camera, path, mode, tau, occlusion, patches, triangle-cull, freeze, resize, "
                                   "minimise, screenshot, window-screenshot, key, quit)");
      }
    } catch (const InputError&) {
      throw;
    } catch (const UsageError& u) {
      if (e.kind == ViewEvent::Kind::Screenshot || e.kind == ViewEvent::Kind::WindowShot) throw;
      throw InputError(path, u.what());
    } catch (const std::logic_error&) {  // stoul, stof
      throw bad("a number");
    } catch (const std::runtime_error& r) {  // occlusionNamed
      throw InputError(path, r.what());
    }
    if (words >> extra)
      throw InputError(path, where + ": " + command + " takes no more than its arguments ('" + extra + "' left over)");
    events.push_back(e);
  }
  return events;
}

}  // namespace vgeo
