// quad_corners.cpp: the corners of a quad mesh grouped by vertex (a counting sort, linear time and 4 bytes
// a corner), so that walks around vertices and across edges (limit.cpp, patch.cpp) find "the corner of a
// whose next vertex is b" by scanning a's few corners instead of sorting a table of every directed edge
// (which cost a 5-million-face build a second and 160 MB).
#include <algorithm>

#include "builder.h"

namespace vgeo {

QuadCorners::QuadCorners(const PolygonMesh& mesh) : vertices_(mesh.faceVertices) {
  offsets_.assign(mesh.positions.size() + 1, 0);
  for (uint32_t v : vertices_) offsets_[v + 1]++;
  for (size_t v = 0; v < mesh.positions.size(); v++) offsets_[v + 1] += offsets_[v];
  corners_.resize(vertices_.size());
  std::vector<uint32_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (uint32_t c = 0; c < vertices_.size(); c++) corners_[fill[vertices_[c]]++] = c;
  // The corners' next vertices beside them: a scan for withNext reads a few neighbouring words instead
  // of one face elsewhere in memory a corner (the walks of patch.cpp and limit.cpp are mostly these).
  nextOf_.resize(corners_.size());
  for (size_t i = 0; i < corners_.size(); i++) nextOf_[i] = at(corners_[i], 1);
}

uint32_t QuadCorners::withNext(uint32_t a, uint32_t b) const {
  for (uint32_t i = offsets_[a]; i < offsets_[a + 1]; i++)
    if (nextOf_[i] == b) return corners_[i];
  return UINT32_MAX;
}

uint32_t QuadCorners::withPrev(uint32_t a, uint32_t b) const {
  for (uint32_t i = offsets_[a]; i < offsets_[a + 1]; i++)
    if (at(corners_[i], 3) == b) return corners_[i];
  return UINT32_MAX;
}

PolygonMesh facesAround(const PolygonMesh& mesh, const std::vector<glm::vec3>& positions, const QuadCorners& q,
                        const uint32_t* vertices, uint32_t count, uint32_t firstFace) {
  std::vector<uint32_t> faces;
  if (firstFace != UINT32_MAX) faces.push_back(firstFace);
  for (uint32_t k = 0; k < count; k++)
    for (uint32_t i = q.offsets()[vertices[k]]; i < q.offsets()[vertices[k] + 1]; i++)
      if (std::find(faces.begin(), faces.end(), q.corners()[i] / 4) == faces.end()) faces.push_back(q.corners()[i] / 4);
  PolygonMesh out;
  std::vector<uint32_t> vertexOf(vertices, vertices + count);  // local vertex -> mesh vertex
  for (uint32_t v : vertexOf) out.positions.push_back(positions[v]);
  for (uint32_t f : faces) {
    uint32_t local[4];
    for (uint32_t k = 0; k < 4; k++) {
      const uint32_t v = mesh.face(f)[k];
      auto it = std::find(vertexOf.begin(), vertexOf.end(), v);
      local[k] = uint32_t(it - vertexOf.begin());
      if (it == vertexOf.end()) {
        vertexOf.push_back(v);
        out.positions.push_back(positions[v]);
      }
    }
    out.addFace(local, 4);
  }
  return out;
}

}  // namespace vgeo
