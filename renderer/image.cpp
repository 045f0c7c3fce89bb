// image.cpp: PNG output through stb_image_write (Debian's libstb).
#include "image.h"

#include <stb/stb_image_write.h>
#include <unistd.h>

#include <cstdio>
#include <stdexcept>

namespace vgeo {

void writePng(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba) {
  std::string temp = path + ".tmp." + std::to_string(::getpid()) + ".png";
  if (!stbi_write_png(temp.c_str(), int(width), int(height), 4, rgba.data(), int(width * 4))) {
    std::remove(temp.c_str());
    throw std::runtime_error(path + ": cannot write the PNG");
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    std::remove(temp.c_str());
    throw std::runtime_error(path + ": cannot rename the finished PNG into place");
  }
}

}  // namespace vgeo
