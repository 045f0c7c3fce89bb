// quad_corners.cpp: the corners of a quad mesh grouped by vertex (a counting sort, linear time and 4 bytes
// a corner), so that walks around vertices and across edges (limit.cpp, patch.cpp) find "the corner of a
// whose next vertex is b" by scanning a's few corners instead of sorting a table of every directed edge
// (which cost a 5-million-face build a second and 160 MB).
#include "builder.h"

namespace vgeo {

QuadCorners::QuadCorners(const PolygonMesh& mesh) : vertices_(mesh.faceVertices) {
  offsets_.assign(mesh.positions.size() + 1, 0);
  for (uint32_t v : vertices_) offsets_[v + 1]++;
  for (size_t v = 0; v < mesh.positions.size(); v++) offsets_[v + 1] += offsets_[v];
  corners_.resize(vertices_.size());
  std::vector<uint32_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (uint32_t c = 0; c < vertices_.size(); c++) corners_[fill[vertices_[c]]++] = c;
}

uint32_t QuadCorners::withNext(uint32_t a, uint32_t b) const {
  for (uint32_t i = offsets_[a]; i < offsets_[a + 1]; i++)
    if (at(corners_[i], 1) == b) return corners_[i];
  return UINT32_MAX;
}

uint32_t QuadCorners::withPrev(uint32_t a, uint32_t b) const {
  for (uint32_t i = offsets_[a]; i < offsets_[a + 1]; i++)
    if (at(corners_[i], 3) == b) return corners_[i];
  return UINT32_MAX;
}

}  // namespace vgeo
