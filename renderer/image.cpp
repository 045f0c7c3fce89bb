// image.cpp: PNG output through stb_image_write (Debian's libstb).
#include "image.h"

#include <stb/stb_image_write.h>

#include "../common/atomic_file.h"

namespace vgeo {

void writePng(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba) {
  // Encoded in memory, then written as one checked, atomic file: stb's own file writer does not check
  // its writes, and left a truncated PNG on a full disk.
  std::string png;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
  };
  if (!stbi_write_png_to_func(append, &png, int(width), int(height), 4, rgba.data(), int(width * 4)))
    throw OutputError(path, "cannot encode the PNG");
  writeFileAtomically(path, png);
}

}  // namespace vgeo
