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
  // A regular file is read at once into a string of its size: a stream's growing buffer copied a
  // large file twice and held up to twice its size.
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size > 0 && in) {
    std::string data(size_t(size), '\0');
    in.read(data.data(), size);
    if (in.gcount() == size && in.peek() == std::char_traits<char>::eof()) return data;
    in.clear();
    in.seekg(0, std::ios::beg);  // it changed while read: read it as a stream
  }
  in.clear();
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
