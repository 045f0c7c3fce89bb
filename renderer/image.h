// image.h: writing the rendered image (image.cpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace vgeo {

// Writes RGBA8 pixels as a PNG through a temporary file and a rename; throws std::runtime_error.
void writePng(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba);

// Whether an RGBA8 pixel of a frame shows geometry: anything but the clear colour (draw.frag never
// outputs it: its darkest lit value is brighter).
inline bool isCovered(const uint8_t* pixel) { return pixel[0] > 12 || pixel[1] > 12 || pixel[2] > 16; }
// Pixels of an RGBA8 frame that show geometry.
inline uint64_t coveredPixels(const std::vector<uint8_t>& rgba) {
  uint64_t covered = 0;
  for (size_t i = 0; i + 3 < rgba.size(); i += 4) covered += isCovered(&rgba[i]);
  return covered;
}

// Pixels of a VGEO_MODE_PATCH frame drawn by the patch draw: tinted by their factor, where the
// triangles are grey.
inline uint64_t patchPixels(const std::vector<uint8_t>& rgba) {
  uint64_t tinted = 0;
  for (size_t i = 0; i + 3 < rgba.size(); i += 4) {
    const uint8_t* p = &rgba[i];
    int lo = std::min({p[0], p[1], p[2]}), hi = std::max({p[0], p[1], p[2]});
    tinted += isCovered(p) && hi - lo > 8;
  }
  return tinted;
}

}  // namespace vgeo
