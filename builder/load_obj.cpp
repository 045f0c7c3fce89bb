// load_obj.cpp: Wavefront OBJ reader. Keeps polygons (faces of any size); reads `v`, `vn` and `f`
// records: positions, connectivity and the shading normals a face's corners name (v//vn, v/vt/vn). A
// corner without a normal, in a file whose other corners have them, shades with its face's normal.
// All objects and groups of the file become one mesh.
#include <algorithm>

#include "text_reader.h"

namespace vgeo {

namespace {
// The line of the file's face record number `face` (0-based), for an error found after reading: lines
// are not kept for every face, which on a large file would take more memory than the faces.
size_t lineOfFace(const std::string& data, const std::string& path, size_t face) {
  TextReader in(data, path);
  for (size_t seen = 0;; in.skipLine()) {
    in.skipWhitespaceAndComments();
    if (in.atEnd()) return in.line();
    if (in.token() == "f" && seen++ == face) return in.line();
  }
}
}  // namespace

SourceScene loadObj(const std::string& path) {
  std::string data = readWholeFile(path);
  TextReader in(data, path);
  PolygonMesh mesh;
  std::vector<glm::vec3> normals;  // vn records
  // A corner's vn index (0-based), -1 for none; empty until some corner names a normal (most large
  // files have none, and this list would be the largest of the load).
  std::vector<int64_t> cornerNormal;
  std::vector<uint32_t> corners;
  std::vector<int64_t> rawCorners, rawNormals;
  while (true) {
    in.skipWhitespaceAndComments();
    if (in.atEnd()) break;
    std::string_view keyword = in.token();
    if (keyword == "v") {
      glm::vec3 p;
      for (int i = 0; i < 3; i++)
        if (!in.tryNumber(p[i])) in.fail("vertex needs three numbers");
      mesh.positions.push_back(p);
    } else if (keyword == "vn") {
      glm::vec3 n;
      for (int i = 0; i < 3; i++)
        if (!in.tryNumber(n[i])) in.fail("normal needs three numbers");
      normals.push_back(n);
    } else if (keyword == "f") {
      rawCorners.clear();
      rawNormals.clear();
      while (!in.atLineEnd()) {
        std::string_view whole = in.token();
        std::string_view t = whole.substr(0, whole.find('/'));  // v/vt/vn: the position index comes first
        int64_t normalIndex = -1;
        size_t second = whole.find('/', t.size() + 1);
        if (t.size() < whole.size() && second != std::string_view::npos && second + 1 < whole.size()) {
          std::string_view n = whole.substr(second + 1);
          int64_t value = 0;
          auto [nend, nec] = std::from_chars(n.data(), n.data() + n.size(), value);
          if (nec != std::errc() || nend != n.data() + n.size() || value == 0)
            in.fail("bad normal index '" + std::string(n) + "'");
          if (value < 0) value += int64_t(normals.size()) + 1;
          if (value <= 0) in.fail("normal index " + std::string(n) + " refers before the first normal");
          normalIndex = value - 1;
        }
        rawNormals.push_back(normalIndex);
        int64_t index = 0;
        auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), index);
        if (ec != std::errc() || end != t.data() + t.size() || index == 0)
          in.fail("bad face index '" + std::string(t) + "'");
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
      const bool named = std::any_of(rawNormals.begin(), rawNormals.end(), [](int64_t n) { return n >= 0; });
      if (named && cornerNormal.empty()) cornerNormal.assign(mesh.faceVertices.size(), -1);
      mesh.addFace(corners.data(), corners.size());
      if (!cornerNormal.empty()) cornerNormal.insert(cornerNormal.end(), rawNormals.begin(), rawNormals.end());
    }
    in.skipLine();
  }
  // Positive indices may point forward, so ranges are checked once every vertex is known.
  for (size_t f = 0; f < mesh.faceCount(); f++)
    for (uint32_t i = 0; i < mesh.faceSize(f); i++)
      if (mesh.face(f)[i] >= mesh.positions.size())
        throw InputError(path, "line " + std::to_string(lineOfFace(data, path, f)) + ": face index " +
                                   std::to_string(mesh.face(f)[i] + 1) + " is out of range (" +
                                   std::to_string(mesh.positions.size()) + " vertices)");
  for (size_t f = 0; f < mesh.faceCount() && !cornerNormal.empty(); f++)
    for (uint32_t i = 0; i < mesh.faceSize(f); i++) {
      int64_t n = cornerNormal[mesh.faceStart[f] + i];
      if (n >= int64_t(normals.size()))
        throw InputError(path, "line " + std::to_string(lineOfFace(data, path, f)) + ": normal index " +
                                   std::to_string(n + 1) + " is out of range (" + std::to_string(normals.size()) +
                                   " normals)");
    }
  if (!cornerNormal.empty()) {
    mesh.cornerNormals.resize(mesh.faceVertices.size(), glm::vec3(0.0f));  // zero: its face's normal
    for (size_t c = 0; c < mesh.faceVertices.size(); c++)
      if (cornerNormal[c] >= 0) mesh.cornerNormals[c] = normals[size_t(cornerNormal[c])];
  }
  return singleMeshScene(std::move(mesh));
}

}  // namespace vgeo
