// fuzz_options.cpp: a libFuzzer target for the command line's value parsers (cli/options.h,
// cli/commands.h, cli/bench.h): sizes, cameras, directions, bounded numbers, lists and the named
// choices. The contract: any text is either a value or a UsageError / std::runtime_error with a cause;
// never a crash, undefined behaviour, a wrapped number (a size past 16384, a float past its range) or a
// value that is not finite. The first byte picks the parser, the rest is the option's text.
#include <cmath>
#include <string>

#include "../../cli/bench.h"
#include "../../cli/commands.h"
#include "../../cli/options.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    switch (data[0] % 8) {
      case 0: {
        uint32_t w = 0, h = 0;
        if (vgeo::parseSize(text, w, h) && (w == 0 || h == 0 || w > 16384 || h > 16384)) __builtin_trap();
        break;
      }
      case 1: {
        const vgeo::Camera c = vgeo::parseCameraOption("--camera", text, 60.0f);
        for (int i = 0; i < 3; i++)
          if (!std::isfinite(c.eye[i]) || !std::isfinite(c.target[i])) __builtin_trap();
        (void)vgeo::makeView(c, 64, 48, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));  // finite or not, never a crash
        break;
      }
      case 2: {
        const glm::vec3 d = vgeo::parseDirectionOption("--light", text);
        if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z)) __builtin_trap();
        break;
      }
      case 3: {
        std::string copy = text;
        if (vgeo::finiteBetween(0.0, INFINITY)(copy).empty() && !std::isfinite(float(std::stod(text))))
          __builtin_trap();
        break;
      }
      case 4:
        (void)vgeo::parseList<float>(text);
        break;
      case 5:
        (void)vgeo::parseList<uint32_t>(text);
        break;
      case 6:
        (void)vgeo::occlusionNamed("--occlusion", text);
        break;
      default:
        (void)vgeo::traversalNamed("--traversal", text);
        (void)vgeo::rasterNamed("--raster", text);
        break;
    }
  } catch (const vgeo::UsageError&) {
  } catch (const std::runtime_error&) {
    // The expected answer to a bad value.
  }
  return 0;
}
