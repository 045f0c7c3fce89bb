// view_script.h: the viewer's script files (docs/viewer.md): timed events, a line each.
#pragma once

#include <string>
#include <vector>

#include "../viewer/viewer.h"

namespace vgeo {

// Reads `path`: its events in frame order. A bad line is an InputError naming the file, the line and
// the cause; a screenshot path that cannot be written is a UsageError before anything is drawn.
std::vector<ViewEvent> readViewScript(const std::string& path, float fovYDegrees,
                                      const std::vector<std::string>& inputs);

}  // namespace vgeo
