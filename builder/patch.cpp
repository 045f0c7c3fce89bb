// patch.cpp: which control points make the limit-surface patch of a face of a Catmull-Clark quad mesh.
// - Regular face (four interior corners of valence 4): away from extraordinary vertices the limit
//   surface is the uniform bicubic B-spline of the control mesh (Catmull & Clark 1978): its 4 x 4
//   neighbourhood, found by walking across the face's edges and around its corners (quad_corners.cpp).
// - One extraordinary interior corner: the 2N + 8 control points of Stam's exact evaluation (1998),
//   evaluated by local subdivision (shaders/patch_eval.h). After one round of Catmull-Clark every
//   extraordinary vertex is isolated by regular ones, so from --subdiv 2 every interior face is one of
//   these two (from --subdiv 1 too when the input is all quads).
// - Faces on a boundary whose corners are regular there (two faces at a boundary vertex, one at a corner):
//   the boundary rules of subdivide.cpp are the B-spline's with the points beyond the boundary mirrored
//   across it (phantom points 2 b - a, as in OpenSubdiv's regular boundary patches).
// Anything else (two extraordinary corners, an extraordinary vertex on a boundary) is left to
// mesh_patches.cpp, which subdivides such a face locally.
#include "../common/parallel.h"
#include "builder.h"

namespace vgeo {

Patcher::Patcher(const PolygonMesh& mesh, int threads) : mesh_(mesh), corners_(mesh, threads) {
  quads_ = allQuads(mesh, threads);
  // A local neighbourhood (mesh_patches.cpp's trees) asks for a few of its vertices: found as asked.
  constexpr size_t kKindsKeptFrom = 4096;
  if (!quads_ || mesh.faceCount() < kKindsKeptFrom) return;
  kinds_.resize(mesh.positions.size());
  parallelForRanges(
      kinds_.size(), threads,
      [&](size_t begin, size_t end) {
        for (size_t v = begin; v < end; v++) kinds_[v] = findKind(uint32_t(v));
      },
      kHeavyRange);
}

// How a vertex's neighbourhood looks to the B-spline rules: interior of valence 4, on a boundary with
// two faces (the boundary is a cubic B-spline there) or with one (a corner, which stays put).
// An edge v -> n has a reverse where some face has n before v: where one of v's own corners has n
// before it, so v's corners alone tell (a scan of each neighbour's corners was a cache miss each).
Patcher::VertexKind Patcher::findKind(uint32_t v) const {
  const QuadCorners& q = corners_;
  const uint32_t first = q.offsets()[v], faces = q.offsets()[v + 1] - first;
  uint32_t open = 0;  // outgoing edges without a reverse
  for (uint32_t i = first; i < first + faces; i++) {
    const uint32_t n = q.at(q.corners()[i], 1);
    bool reversed = false;
    for (uint32_t j = first; j < first + faces && !reversed; j++) reversed = q.at(q.corners()[j], 3) == n;
    open += !reversed;
  }
  if (open == 0) return faces == 4 ? VertexKind::Interior : VertexKind::Irregular;
  if (open == 1 && faces == 2) return VertexKind::Boundary;
  if (open == 1 && faces == 1) return VertexKind::Corner;
  return VertexKind::Irregular;
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
  uint32_t cA = q.withNext(f0, e0), cB = q.withNext(e0, fLast), cC = UINT32_MAX, cD = q.withNext(e1, f0),
           cE = UINT32_MAX;
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
  if (!quads_) return patch;
  const QuadCorners& q = corners_;
  const uint32_t* v = mesh_.face(face);
  bool open[4];        // edge k (v[k] -> v[k+1]) on a boundary
  uint32_t across[4];  // else the corner of v[k+1] across it, in the face beyond
  for (uint32_t k = 0; k < 4; k++) {
    const uint32_t c = across[k] = q.withNext(v[(k + 1) % 4], v[k]);
    if (c != UINT32_MAX) patch.neighbours[k] = (c / 4) << 2 | (c % 4);
    open[k] = c == UINT32_MAX;
  }
  VertexKind kinds[4];
  int irregular = 0, irregularCorner = 0;
  for (int k = 0; k < 4; k++) {
    kinds[k] = kinds_.empty() ? findKind(v[k]) : kinds_[v[k]];
    // A corner's kind must match the face's edges at it: both open at a corner, one at a boundary vertex.
    const int openEdges = int(open[k]) + int(open[(k + 3) % 4]);
    const int expected = kinds[k] == VertexKind::Interior ? 0 : kinds[k] == VertexKind::Boundary ? 1 : 2;
    if (kinds[k] == VertexKind::Irregular || openEdges != expected) irregular++, irregularCorner = k;
  }
  if (irregular == 1 && kinds[irregularCorner] == VertexKind::Irregular && open[0] + open[1] + open[2] + open[3] == 0) {
    if (!ring(face, uint32_t(irregularCorner), patch)) patch.kind = VGEO_PATCH_NONE;
    return patch;
  }
  if (irregular > 0) return patch;
  // Grid cells P[row][col]; the face is v0 = P[1][1], v1 = P[1][2], v2 = P[2][2], v3 = P[2][1]. Across
  // edge k (v[k] -> v[k+1]) lies the face v[k+1], v[k], near[k], far[k] (near[k] next to v[k]); around
  // corner v[k], the face near[k], v[k], far[k-1], diagonal[k]. Beyond a boundary the points are mirrored
  // (Catmull-Clark's boundary rules are the B-spline's with these phantom points): across open edge k,
  // near[k] = 2 v[k] - v[k-1] and far[k] = 2 v[k+1] - v[k+2]; a diagonal cell mirrors its row or column.
  static const int kEdgeCells[4][2][2] = {{{0, 1}, {0, 2}}, {{1, 3}, {2, 3}}, {{3, 2}, {3, 1}}, {{2, 0}, {1, 0}}};
  static const int kCornerCells[4][2] = {{0, 0}, {0, 3}, {3, 3}, {3, 0}};
  static const int kFaceCells[4][2] = {{1, 1}, {1, 2}, {2, 2}, {2, 1}};
  auto slot = [](const int cell[2]) { return uint8_t(4 * cell[0] + cell[1]); };
  auto mirror = [&](uint8_t target, uint8_t a, uint8_t b) {
    patch.points[target] = UINT32_MAX;
    patch.phantoms[patch.phantomCount][0] = target, patch.phantoms[patch.phantomCount][1] = a,
    patch.phantoms[patch.phantomCount][2] = b;
    patch.phantomCount++;
  };
  uint32_t nearV[4], farV[4];
  for (int k = 0; k < 4; k++) {
    patch.points[slot(kFaceCells[k])] = v[k];
    const uint8_t nearSlot = slot(kEdgeCells[k][0]), farSlot = slot(kEdgeCells[k][1]);
    if (open[k]) {
      mirror(nearSlot, slot(kFaceCells[k]), slot(kFaceCells[(k + 3) % 4]));
      mirror(farSlot, slot(kFaceCells[(k + 1) % 4]), slot(kFaceCells[(k + 2) % 4]));
      continue;
    }
    nearV[k] = q.at(across[k], 2);
    farV[k] = q.at(across[k], 3);
    patch.points[nearSlot] = nearV[k];
    patch.points[farSlot] = farV[k];
  }
  for (int k = 0; k < 4; k++) {
    const int before = (k + 3) % 4;
    const uint8_t cornerSlot = slot(kCornerCells[k]);
    if (open[k]) {  // mirror the column beyond edge k - 1 across edge k
      mirror(cornerSlot, slot(kEdgeCells[before][1]), slot(kEdgeCells[before][0]));
    } else if (open[before]) {  // mirror the row beyond edge k across edge k - 1
      mirror(cornerSlot, slot(kEdgeCells[k][0]), slot(kEdgeCells[k][1]));
    } else {
      uint32_t c = q.withNext(nearV[k], v[k]);
      if (c == UINT32_MAX || q.at(c, 2) != farV[before]) {
        patch.kind = VGEO_PATCH_NONE;  // the neighbourhood does not close up like a grid
        patch.phantomCount = 0;
        return patch;
      }
      patch.points[cornerSlot] = q.at(c, 3);
    }
  }
  patch.kind = VGEO_PATCH_REGULAR;
  patch.pointCount = 16;
  return patch;
}

}  // namespace vgeo
