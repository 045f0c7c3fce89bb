// patch.cpp: the limit-surface patch of each face of a Catmull-Clark quad mesh, and its chord errors.
// - Regular face (four interior corners of valence 4): away from extraordinary vertices the limit
//   surface is the uniform bicubic B-spline of the control mesh (Catmull & Clark 1978): its 4 x 4
//   neighbourhood, found by walking across the face's edges and around its corners (quad_corners.cpp).
// - One extraordinary interior corner: the 2N + 8 control points of Stam's exact evaluation (1998),
//   evaluated by local subdivision (shaders/patch_eval.h). After one round of Catmull-Clark every
//   extraordinary vertex is isolated by regular ones, so from --subdiv 2 every interior face is one of
//   these two (from --subdiv 1 too when the input is all quads).
// - Faces on a boundary, or with two extraordinary corners (--subdiv 1 of a triangle mesh), get no patch:
//   the renderer draws them as their leaf triangles, with their edges at factor 1.
// Chord errors measure how far the leaf triangles are from the surface (DESIGN.md, leaves): they are the
// leaf clusters' self error and drive the tessellation factors.
#include <algorithm>
#include <array>
#include <cmath>

#include "../common/parallel.h"
#include "builder.h"

namespace vgeo {
namespace {

double pointSegmentDistance(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b) {
  glm::dvec3 ab = b - a;
  double len2 = glm::dot(ab, ab);
  double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

}  // namespace

Patcher::Patcher(const PolygonMesh& mesh) : mesh_(mesh), corners_(mesh) {
  quads_ = true;
  for (size_t f = 0; f < mesh.faceCount(); f++) quads_ = quads_ && mesh.faceSize(f) == 4;
}

// Regular vertex: four faces, none on a boundary (every outgoing edge has its reverse).
bool Patcher::regular(uint32_t v) const {
  const QuadCorners& q = corners_;
  if (q.offsets()[v + 1] - q.offsets()[v] != 4) return false;
  for (uint32_t i = q.offsets()[v]; i < q.offsets()[v + 1]; i++)
    if (q.withNext(q.at(q.corners()[i], 1), v) == UINT32_MAX) return false;
  return true;
}

// The ring of the face whose corner `corner` is extraordinary (the other three regular): walk around
// the vertex through faces (v, e_i, f_i, e_(i+1)), then read the 7 outer points off the faces A..E
// beside the patch (patch_eval.h names them).
bool Patcher::ring(uint32_t face, uint32_t corner, FacePatch& out) const {
  const QuadCorners& q = corners_;
  const uint32_t v = mesh_.face(face)[corner];
  const uint32_t valence = q.offsets()[v + 1] - q.offsets()[v];
  if (valence < 3 || valence > VGEO_MAX_VALENCE) return false;
  uint32_t* p = out.points;
  p[0] = v;
  uint32_t c = 4 * face + corner;
  for (uint32_t i = 0; i < valence; i++) {
    p[1 + 2 * i] = q.at(c, 1);
    p[2 + 2 * i] = q.at(c, 2);
    c = q.withNext(v, q.at(c, 3));
    if (c == UINT32_MAX) return false;  // a boundary vertex
  }
  if (c != 4 * face + corner) return false;
  const uint32_t e0 = p[1], f0 = p[2], e1 = p[3], f1 = p[4], fLast = p[2 * valence];
  uint32_t cA = q.withNext(f0, e0), cB = q.withNext(e0, fLast), cC = UINT32_MAX, cD = q.withNext(e1, f0), cE = UINT32_MAX;
  if (cA == UINT32_MAX || cB == UINT32_MAX || cD == UINT32_MAX) return false;
  cC = q.withNext(f0, q.at(cA, 3));
  cE = q.withNext(e1, q.at(cD, 3));
  if (cC == UINT32_MAX || cE == UINT32_MAX) return false;
  uint32_t o[7] = {q.at(cB, 2), q.at(cA, 2), q.at(cA, 3), q.at(cC, 2), q.at(cC, 3), q.at(cD, 3), q.at(cE, 2)};
  // The neighbourhood must close up as in a regular grid.
  if (q.at(cB, 3) != o[1] || q.at(cD, 2) != o[4] || q.at(cE, 3) != f1) return false;
  for (int k = 0; k < 7; k++) p[2 * valence + 1 + k] = o[k];
  out.kind = VGEO_PATCH_RING;
  out.corner = corner;
  out.valence = valence;
  out.pointCount = 2 * valence + 8;
  return true;
}

FacePatch Patcher::patch(uint32_t face) const {
  FacePatch patch;
  for (uint32_t& n : patch.neighbours) n = UINT32_MAX;
  if (!quads_) return patch;
  const QuadCorners& q = corners_;
  const uint32_t* v = mesh_.face(face);
  for (uint32_t k = 0; k < 4; k++) {
    uint32_t c = q.withNext(v[(k + 1) % 4], v[k]);
    if (c != UINT32_MAX) patch.neighbours[k] = (c / 4) << 2 | (c % 4);
  }
  bool isRegular[4];
  int irregular = 0, irregularCorner = 0;
  for (int k = 0; k < 4; k++) {
    isRegular[k] = regular(v[k]);
    if (!isRegular[k]) irregular++, irregularCorner = k;
  }
  if (irregular == 1) {
    if (!ring(face, uint32_t(irregularCorner), patch)) patch.kind = VGEO_PATCH_NONE;
    return patch;
  }
  if (irregular > 1) return patch;
  // Grid cells P[row][col]; the face is v0 = P[1][1], v1 = P[1][2], v2 = P[2][2], v3 = P[2][1]. Across
  // edge k (v[k] -> v[k+1]) lies the face v[k+1], v[k], near[k], far[k] (near[k] next to v[k]); around
  // corner v[k], the face near[k], v[k], far[k-1], diagonal[k].
  static const int kEdgeCells[4][2][2] = {{{0, 1}, {0, 2}}, {{1, 3}, {2, 3}}, {{3, 2}, {3, 1}}, {{2, 0}, {1, 0}}};
  static const int kCornerCells[4][2] = {{0, 0}, {0, 3}, {3, 3}, {3, 0}};
  static const int kFaceCells[4][2] = {{1, 1}, {1, 2}, {2, 2}, {2, 1}};
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
  patch.kind = VGEO_PATCH_REGULAR;
  patch.pointCount = 16;
  return patch;
}

glm::vec3 evaluateFacePatch(const FacePatch& patch, const std::vector<glm::vec3>& controlPoints, float s, float t, glm::vec3* normal) {
  glm::vec3 points[VGEO_MAX_RING], n;
  for (uint32_t i = 0; i < patch.pointCount; i++) points[i] = controlPoints[patch.points[i]];
  glm::vec3 p = shaderio::evaluatePatch(patch.kind, patch.corner, int(patch.valence), points, s, t, n);
  if (normal) *normal = n;
  return p;
}

std::vector<PatchErrors> patchChordErrors(const PolygonMesh& limitMesh, const std::vector<glm::vec3>& controlPoints, uint32_t threads) {
  const size_t faceCount = limitMesh.faceCount();
  std::vector<PatchErrors> own(faceCount), merged(faceCount);
  if (controlPoints.size() != limitMesh.positions.size()) return merged;
  std::vector<std::array<uint32_t, 4>> neighbours(faceCount);
  Patcher patcher(limitMesh);
  const std::vector<glm::vec3>& x = limitMesh.positions;
  // Quarter parameters: the bulge of a bicubic between its corners peaks near the middle; 12% more
  // covers what falls between the samples (tests/test_patch.cpp checks against 16ths). An edge is
  // measured once, by the face of the lower index (or the only one, on a boundary).
  constexpr float kSlack = 1.12f;
  static const float kCorner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  parallelFor(faceCount, int(threads), [&](size_t f) {
    FacePatch patch = patcher.patch(uint32_t(f));
    for (int k = 0; k < 4; k++) neighbours[f][size_t(k)] = patch.neighbours[k];
    if (patch.kind == VGEO_PATCH_NONE) return;
    own[f].patched = true;
    const uint32_t* v = limitMesh.face(f);
    PatchErrors& e = own[f];
    for (int k = 0; k < 4; k++) {
      if (patch.neighbours[k] != UINT32_MAX && (patch.neighbours[k] >> 2) < f) continue;
      glm::dvec3 a(x[v[k]]), b(x[v[(k + 1) % 4]]);
      double worst = 0.0;
      for (int i = 1; i < 4; i++) {
        float u = float(i) / 4.0f;
        float s = kCorner[k][0] + u * (kCorner[(k + 1) % 4][0] - kCorner[k][0]), t = kCorner[k][1] + u * (kCorner[(k + 1) % 4][1] - kCorner[k][1]);
        glm::dvec3 p(evaluateFacePatch(patch, controlPoints, s, t));
        worst = std::max(worst, pointSegmentDistance(p, a, b));
      }
      e.edge[k] = float(worst * kSlack);
    }
    std::vector<uint32_t> tris;
    triangulateFace(x.data(), v, 4, tris);
    double worst = 0.0;
    for (int i = 1; i < 4; i++)
      for (int j = 1; j < 4; j++) {
        glm::dvec3 p(evaluateFacePatch(patch, controlPoints, float(i) / 4.0f, float(j) / 4.0f));
        double d = std::min(pointTriangleDistance(p, x[tris[0]], x[tris[1]], x[tris[2]]), pointTriangleDistance(p, x[tris[3]], x[tris[4]], x[tris[5]]));
        worst = std::max(worst, d);
      }
    e.face = float(worst * kSlack);
  });
  // One value an edge, the measuring face's (0 next to a flat face: the edge stays straight there); a
  // face's error covers its edges'.
  parallelFor(faceCount, int(threads), [&](size_t f) {
    if (!own[f].patched) return;
    PatchErrors& out = merged[f];
    out.patched = true;
    out.face = own[f].face;
    for (int k = 0; k < 4; k++) {
      uint32_t n = neighbours[f][size_t(k)];
      out.edge[k] = n == UINT32_MAX ? own[f].edge[k] : !own[n >> 2].patched ? 0.0f : (n >> 2) < f ? own[n >> 2].edge[n & 3] : own[f].edge[k];
      out.face = std::max(out.face, out.edge[k]);
    }
  });
  return merged;
}

}  // namespace vgeo
