// json_depth.h: how deeply JSON text nests, counted before it is parsed. Parsers and the values they make
// recurse per level (tinygltf's `extras`, copies and error messages of nlohmann::json): a file nested
// 80,000 deep overflowed the stack. The glTF reader and scene files refuse text deeper than
// kMaxJsonDepth; their own structures are under 10 deep.
#pragma once

#include <algorithm>
#include <cstddef>

namespace vgeo {

constexpr int kMaxJsonDepth = 64;

// The deepest nesting of objects and arrays in JSON text (strings skipped); stops counting past `limit`.
inline int jsonDepth(const char* text, size_t size, int limit) {
  int depth = 0, deepest = 0;
  bool inString = false;
  for (size_t i = 0; i < size; i++) {
    const char c = text[i];
    if (inString) {
      if (c == '\\')
        i++;
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '{' || c == '[') {
      deepest = std::max(deepest, ++depth);
      if (deepest > limit) return deepest;
    } else if (c == '}' || c == ']') {
      depth--;
    }
  }
  return deepest;
}

}  // namespace vgeo
