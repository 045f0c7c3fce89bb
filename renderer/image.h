// image.h: writing the rendered image (image.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace vgeo {

// Writes RGBA8 pixels as a PNG through a temporary file and a rename; throws std::runtime_error.
void writePng(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba);

}  // namespace vgeo
