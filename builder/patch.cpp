// patch.cpp: the bicubic uniform B-spline patches of a Catmull-Clark quad mesh's regular faces. Away from
// extraordinary vertices and boundaries the limit surface of Catmull-Clark is exactly the uniform bicubic
// B-spline surface of the control mesh (Catmull & Clark 1978), so a face whose four corners are interior
// and of valence 4 is the patch of its 4 x 4 neighbourhood of control points. The neighbourhood is found
// by walking across the face's edges and around its corners (quad_corners.cpp); faces next to an
// extraordinary vertex or a boundary get no patch here (feature-adaptive isolation or Gregory patches
// would cover them; not yet).
#include <algorithm>

#include "builder.h"

namespace vgeo {

BsplinePatcher::BsplinePatcher(const PolygonMesh& mesh) : mesh_(mesh), corners_(mesh) {
  quads_ = true;
  for (size_t f = 0; f < mesh.faceCount(); f++) quads_ = quads_ && mesh.faceSize(f) == 4;
}

// Regular vertex: four faces, none on a boundary (every outgoing edge has its reverse).
bool BsplinePatcher::regular(uint32_t v) const {
  const QuadCorners& q = corners_;
  if (q.offsets()[v + 1] - q.offsets()[v] != 4) return false;
  for (uint32_t i = q.offsets()[v]; i < q.offsets()[v + 1]; i++)
    if (q.withNext(q.at(q.corners()[i], 1), v) == UINT32_MAX) return false;
  return true;
}

shaderio::BsplinePatch BsplinePatcher::patch(uint32_t face) const {
  shaderio::BsplinePatch patch{};
  patch.points[0] = VGEO_NO_PATCH;
  if (!quads_) return patch;
  const QuadCorners& q = corners_;
  // Grid cells P[row][col]; the face is v0 = P[1][1], v1 = P[1][2], v2 = P[2][2], v3 = P[2][1]. Across
  // edge k (v[k] -> v[k+1]) lies the face v[k+1], v[k], near[k], far[k] (near[k] next to v[k]); around
  // corner v[k], the face near[k], v[k], far[k-1], diagonal[k].
  static const int kEdgeCells[4][2][2] = {{{0, 1}, {0, 2}}, {{1, 3}, {2, 3}}, {{3, 2}, {3, 1}}, {{2, 0}, {1, 0}}};
  static const int kCornerCells[4][2] = {{0, 0}, {0, 3}, {3, 3}, {3, 0}};
  static const int kFaceCells[4][2] = {{1, 1}, {1, 2}, {2, 2}, {2, 1}};
  const uint32_t* v = mesh_.face(face);
  if (!regular(v[0]) || !regular(v[1]) || !regular(v[2]) || !regular(v[3])) return patch;
  uint32_t grid[4][4], nearV[4], farV[4];
  for (int k = 0; k < 4; k++) {
    grid[kFaceCells[k][0]][kFaceCells[k][1]] = v[k];
    uint32_t c = q.withNext(v[(k + 1) % 4], v[k]);
    if (c == UINT32_MAX) return patch;
    nearV[k] = q.at(c, 2);
    farV[k] = q.at(c, 3);
  }
  for (int k = 0; k < 4; k++) {
    uint32_t c = q.withNext(nearV[k], v[k]);
    if (c == UINT32_MAX || q.at(c, 2) != farV[(k + 3) % 4]) return patch;
    grid[kEdgeCells[k][0][0]][kEdgeCells[k][0][1]] = nearV[k];
    grid[kEdgeCells[k][1][0]][kEdgeCells[k][1][1]] = farV[k];
    grid[kCornerCells[k][0]][kCornerCells[k][1]] = q.at(c, 3);
  }
  for (int r = 0; r < 4; r++)
    for (int col = 0; col < 4; col++) patch.points[4 * r + col] = grid[r][col];
  return patch;
}

std::vector<shaderio::BsplinePatch> bsplinePatches(const PolygonMesh& mesh) {
  BsplinePatcher patcher(mesh);
  std::vector<shaderio::BsplinePatch> patches(mesh.faceCount());
  for (size_t f = 0; f < patches.size(); f++) patches[f] = patcher.patch(uint32_t(f));
  return patches;
}

glm::dvec3 evaluateBspline(const glm::vec3 points[16], double u, double v, glm::dvec3* du, glm::dvec3* dv) {
  auto basis = [](double t, double b[4], double d[4]) {
    double s = 1.0 - t;
    b[0] = s * s * s / 6.0;
    b[1] = (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0;
    b[2] = (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0;
    b[3] = t * t * t / 6.0;
    d[0] = -0.5 * s * s;
    d[1] = 1.5 * t * t - 2.0 * t;
    d[2] = -1.5 * t * t + t + 0.5;
    d[3] = 0.5 * t * t;
  };
  double bu[4], du1[4], bv[4], dv1[4];
  basis(u, bu, du1);
  basis(v, bv, dv1);
  glm::dvec3 p(0.0), pu(0.0), pv(0.0);
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 4; c++) {
      glm::dvec3 q(points[4 * r + c]);
      p += bv[r] * bu[c] * q;
      pu += bv[r] * du1[c] * q;
      pv += dv1[r] * bu[c] * q;
    }
  if (du) *du = pu;
  if (dv) *dv = pv;
  return p;
}

}  // namespace vgeo
