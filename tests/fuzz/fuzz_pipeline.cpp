// fuzz_pipeline.cpp: a libFuzzer target over the whole builder: OBJ or OFF bytes (the first byte picks
// the format and 0-2 Catmull-Clark levels), built, written, read back and checked. The contract: the
// build throws InputError, or its file loads and passes `vgeo check`'s invariants (DESIGN: watertight
// cuts, monotonic errors, patches through their leaf vertices). A file the builder writes and its own
// checker refuses is a bug, as are crashes, sanitizer reports and other exceptions.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "../../builder/build_scene.h"
#include "../../reference/cut.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1 || size > 4096) return 0;  // small cages keep executions fast; size is not the point
  static const std::string dir = [] {
    std::string d =
        (std::filesystem::temp_directory_path() / ("vgeo_fuzz_pipeline_" + std::to_string(::getpid()))).string();
    std::filesystem::create_directories(d);
    return d;
  }();
  const std::string path = dir + (data[0] & 1 ? "/input.off" : "/input.obj");
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  std::fwrite(data + 1, 1, size - 1, f);
  std::fclose(f);
  vgeo::SceneBuildOptions options;
  options.subdivisionLevels = (data[0] >> 1) % 3;
  vgeo::VgeoData built;
  try {
    vgeo::SceneBuildStats stats;
    built = vgeo::buildScene(path, options, stats);
  } catch (const vgeo::InputError&) {
    return 0;
  }
  std::vector<uint8_t> bytes = vgeo::serializeVgeo(built);
  vgeo::VgeoData read = vgeo::parseVgeo(bytes.data(), bytes.size(), "built.vgeo");  // must not throw
  vgeo::CheckResult result = vgeo::checkVgeo(read, {8, 1});
  if (!result.ok) {
    std::fprintf(stderr, "the builder wrote a file its checker refuses: %s\n", result.firstViolation.c_str());
    std::abort();
  }
  return 0;
}
