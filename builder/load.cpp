// load.cpp: picks the reader for a mesh file by its extension, and reads whole files.
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "text_reader.h"

namespace vgeo {

std::string readWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream data;
  data << in.rdbuf();
  if (in.bad()) throw InputError(path, "read error");
  return std::move(data).str();
}

SourceScene singleMeshScene(PolygonMesh mesh) {
  SourceScene scene;
  scene.meshes.push_back(std::move(mesh));
  scene.meshNames.push_back("mesh");
  scene.instances.push_back({});
  return scene;
}

SourceScene loadMeshFile(const std::string& path, int threads) {
  std::string ext = path.substr(path.find_last_of('.') == std::string::npos ? path.size() : path.find_last_of('.'));
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".obj") return loadObj(path, threads);
  if (ext == ".off") return loadOff(path);
  if (ext == ".ply") return loadPly(path);
  if (ext == ".gltf" || ext == ".glb") return loadGltf(path);
  throw InputError(path, "unknown mesh format '" + ext + "' (expected .obj, .off, .ply, .gltf or .glb)");
}

}  // namespace vgeo
