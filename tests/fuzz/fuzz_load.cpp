// fuzz_load.cpp: a libFuzzer target for one of vgeo's readers, chosen when it is compiled
// (VGEO_FUZZ_INPUT: obj, off, ply, gltf, glb, vgeo or json). The contract under test: any bytes either
// load or throw InputError (one line naming the file); anything else (a crash, a sanitizer report, a
// hang, an exception of another kind, memory past libFuzzer's -rss_limit_mb) is a bug. A .vgeo that
// loads must also pass through the checker without harm, and a scene file is read beside a small
// valid .vgeo it may name ("a.vgeo").
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "../../builder/build_scene.h"
#include "../../common/vgeo_file.h"
#include "../../reference/cut.h"
#include "../../renderer/scene.h"

namespace {

const std::string& folder() {
  static const std::string dir = [] {
    std::string d = (std::filesystem::temp_directory_path() / ("vgeo_fuzz_" + std::to_string(::getpid()))).string();
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

void writeBytes(const std::string& path, const uint8_t* data, size_t size) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string kind = VGEO_FUZZ_INPUT;
  try {
    if (kind == "vgeo") {
      vgeo::VgeoData d = vgeo::parseVgeo(data, size, "fuzz.vgeo");
      vgeo::checkVgeo(d, {2, 1});
      return 0;
    }
    if (kind == "json") {
      static bool once = [] {
        // A tetrahedron's .vgeo for the scene to name.
        vgeo::PolygonMesh m;
        m.positions = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
        const uint32_t faces[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
        for (const auto& f : faces) m.addFace(f, 3);
        std::string obj;
        for (const auto& p : m.positions)
          obj += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
        obj += "f 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n";
        writeBytes(folder() + "/t.obj", reinterpret_cast<const uint8_t*>(obj.data()), obj.size());
        vgeo::SceneBuildStats stats;
        vgeo::writeVgeo(vgeo::buildScene(folder() + "/t.obj", {}, stats), folder() + "/a.vgeo");
        return true;
      }();
      (void)once;
      writeBytes(folder() + "/scene.json", data, size);
      vgeo::loadRenderScene(folder() + "/scene.json");
      return 0;
    }
    const std::string path = folder() + "/input." + kind;
    writeBytes(path, data, size);
    vgeo::SourceScene scene = vgeo::loadMeshFile(path);
    for (vgeo::PolygonMesh& mesh : scene.meshes) vgeo::repairMesh(mesh, path);
  } catch (const vgeo::InputError&) {
    // The expected answer to bad bytes.
  }
  return 0;
}
