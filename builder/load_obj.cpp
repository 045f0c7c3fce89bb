// load_obj.cpp: Wavefront OBJ reader. Keeps polygons (faces of any size); reads only `v` and `f`
// records, since the builder needs positions and connectivity (normals are recomputed from the surface).
// All objects and groups of the file become one mesh.
#include "text_reader.h"

namespace vgeo {

SourceScene loadObj(const std::string& path) {
  std::string data = readWholeFile(path);
  TextReader in(data, path);
  PolygonMesh mesh;
  std::vector<uint32_t> corners;
  std::vector<int64_t> rawCorners;
  std::vector<size_t> faceLines;
  while (true) {
    in.skipWhitespaceAndComments();
    if (in.atEnd()) break;
    std::string_view keyword = in.token();
    if (keyword == "v") {
      glm::vec3 p;
      for (int i = 0; i < 3; i++)
        if (!in.tryNumber(p[i])) in.fail("vertex needs three numbers");
      mesh.positions.push_back(p);
    } else if (keyword == "f") {
      rawCorners.clear();
      while (!in.atLineEnd()) {
        std::string_view t = in.token();
        t = t.substr(0, t.find('/'));  // v/vt/vn: the position index comes first
        int64_t index = 0;
        auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), index);
        if (ec != std::errc() || end != t.data() + t.size() || index == 0) in.fail("bad face index '" + std::string(t) + "'");
        // Negative indices count back from the vertices read so far.
        if (index < 0) index += int64_t(mesh.positions.size()) + 1;
        if (index <= 0) in.fail("face index " + std::string(t) + " refers before the first vertex");
        rawCorners.push_back(index - 1);
      }
      corners.clear();
      for (int64_t c : rawCorners) {
        if (c > int64_t(UINT32_MAX) - 1) in.fail("face index too large for 32-bit indices");
        corners.push_back(uint32_t(c));
      }
      mesh.addFace(corners.data(), corners.size());
      faceLines.push_back(in.line());
    }
    in.skipLine();
  }
  // Positive indices may point forward, so ranges are checked once every vertex is known.
  for (size_t f = 0; f < mesh.faceCount(); f++)
    for (uint32_t i = 0; i < mesh.faceSize(f); i++)
      if (mesh.face(f)[i] >= mesh.positions.size())
        throw InputError(path, "line " + std::to_string(faceLines[f]) + ": face index " +
                                   std::to_string(mesh.face(f)[i] + 1) + " is out of range (" +
                                   std::to_string(mesh.positions.size()) + " vertices)");
  return singleMeshScene(std::move(mesh));
}

}  // namespace vgeo
