// load_off.cpp: Object File Format reader (OFF, COFF, NOFF headers; per-element colours after the
// indices are skipped). Polygons are kept.
#include "text_reader.h"

namespace vgeo {

SourceScene loadOff(const std::string& path) {
  const FillLaterVector<char> data = readWholeFile(path);
  TextReader in(std::string_view(data.data(), data.size()), path);
  in.skipWhitespaceAndComments();
  std::string_view header = in.token();
  bool hasNormals = header.find('N') != std::string_view::npos;
  bool hasColors = header.find('C') != std::string_view::npos;
  if (header.size() < 3 || header.substr(header.size() - 3) != "OFF")
    in.fail("not an OFF file (first word is '" + std::string(header.substr(0, 16)) + "')");
  int64_t vertexCount = in.number<int64_t>("vertex count");
  int64_t faceCount = in.number<int64_t>("face count");
  in.number<int64_t>("edge count");
  if (vertexCount < 0 || faceCount < 0) in.fail("negative element count");
  if (vertexCount > int64_t(UINT32_MAX) || faceCount > int64_t(UINT32_MAX))
    in.fail("too many elements for 32-bit indices");
  // Each vertex takes at least 6 bytes ("0 0 0\n"): a count larger than the file can hold is an error,
  // not an allocation.
  if (uint64_t(vertexCount) * 6 > data.size() || uint64_t(faceCount) * 8 > data.size())
    in.fail("truncated: the header promises " + std::to_string(vertexCount) + " vertices and " +
            std::to_string(faceCount) + " faces, more than the file holds");
  PolygonMesh mesh;
  mesh.positions.resize(size_t(vertexCount));
  for (auto& p : mesh.positions) {
    for (int i = 0; i < 3; i++) p[i] = in.number<float>("vertex coordinate");
    if (hasNormals || hasColors) in.skipLine();  // extra per-vertex values
  }
  std::vector<uint32_t> corners;
  for (int64_t f = 0; f < faceCount; f++) {
    int64_t n = in.number<int64_t>("face size");
    if (n < 0 || n > 1 << 20) in.fail("bad face size " + std::to_string(n));
    corners.resize(size_t(n));
    for (auto& c : corners) {
      int64_t index = in.number<int64_t>("face index");
      if (index < 0 || index >= vertexCount)
        in.fail("face index " + std::to_string(index) + " is out of range (" + std::to_string(vertexCount) +
                " vertices)");
      c = uint32_t(index);
    }
    mesh.addFace(corners.data(), corners.size());
    in.skipLine();  // optional face colour
  }
  return singleMeshScene(std::move(mesh));
}

}  // namespace vgeo
