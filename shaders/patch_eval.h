// patch_eval.h: evaluation of a Catmull-Clark limit surface patch, written once in the subset of GLSL and
// C++ (with glm) that both compile, so the builder (chord errors), the tests and the tessellation
// shaders evaluate the same surface with the same arithmetic.
//
// - Regular face (four interior corners of valence 4): the uniform bicubic B-spline patch of its 4 x 4
//   control points (Catmull & Clark 1978).
// - Face with one extraordinary corner of valence N (interior): its "ring" of 2N + 8 control points in
//   Stam's order ("Exact evaluation of Catmull-Clark subdivision surfaces at arbitrary parameter values",
//   SIGGRAPH 1998): the extraordinary vertex; for each sector i the edge neighbour e_i and the face
//   vertex f_i, with face i = (v, e_i, f_i, e_(i+1)) and face 0 the patch; then the 7 outer points of the
//   patch's 4 x 4 neighbourhood. Where Stam projects onto the eigenbasis, this evaluates the same limit by
//   subdividing the ring explicitly: a point at (a, b) with max(a, b) in [2^-(n+1), 2^-n) lies on a
//   regular sub-patch after n + 1 local subdivisions, which is then a B-spline patch (feature-adaptive
//   subdivision, Niessner et al. 2012, done per evaluated point). Tessellated vertices sit at multiples
//   of 1/64 or coarser, so at most 7 rounds of O(N) work each. (a, b) = (0, 0) is the vertex's limit
//   point (Halstead et al. 1993 masks).
// The ring's parameters: a runs from v towards e_0, b from v towards e_1.
// - Anything else (shaderio.h, VGEO_PATCH_TREE): a quadtree of the face subdivided locally, walked down
//   by patchQuadrant to a patch of the kinds above; its last irregular quadrant is bilinear.
#ifndef VGEO_PATCH_EVAL_H
#define VGEO_PATCH_EVAL_H

#define VGEO_MAX_VALENCE 16
#define VGEO_MAX_RING (2 * VGEO_MAX_VALENCE + 8)

#include "shaderio.h"

#ifdef __cplusplus
#include <cmath>
#endif

VGEO_NAMESPACE_BEGIN

// Uniform cubic B-spline basis at t.
VGEO_INLINE vec4 bsplineWeights(float t) {
  float s = 1.0f - t;
  return vec4(s * s * s, 3.0f * t * t * t - 6.0f * t * t + 4.0f, -3.0f * t * t * t + 3.0f * t * t + 3.0f * t + 1.0f,
              t * t * t) /
         6.0f;
}

// Uniform cubic B-spline basis at t, and its derivative.
VGEO_INLINE void bsplineBasis(float t, VGEO_OUT(vec4) b, VGEO_OUT(vec4) d) {
  float s = 1.0f - t;
  b = bsplineWeights(t);
  d = vec4(-0.5f * s * s, 1.5f * t * t - 2.0f * t, -1.5f * t * t + t + 0.5f, 0.5f * t * t);
}

// The bicubic B-spline patch of 16 control points (row by row) at (u, v): u along a row (from p[5] to
// p[6]), v down the columns (from p[5] to p[9]); du, dv its partial derivatives.
VGEO_INLINE vec3 evaluateBspline(vec3 p[16], float u, float v, VGEO_OUT(vec3) du, VGEO_OUT(vec3) dv) {
  vec4 bu, bv, su, sv;
  bsplineBasis(u, bu, su);
  bsplineBasis(v, bv, sv);
  vec3 pos = vec3(0.0f);
  du = vec3(0.0f);
  dv = vec3(0.0f);
  for (int r = 0; r < 4; r++) {
    vec3 row = bu[0] * p[4 * r] + bu[1] * p[4 * r + 1] + bu[2] * p[4 * r + 2] + bu[3] * p[4 * r + 3];
    vec3 rowD = su[0] * p[4 * r] + su[1] * p[4 * r + 1] + su[2] * p[4 * r + 2] + su[3] * p[4 * r + 3];
    pos += bv[r] * row;
    du += bv[r] * rowD;
    dv += sv[r] * row;
  }
  return pos;
}

// evaluateBspline's position alone.
VGEO_INLINE vec3 evaluateBsplinePosition(vec3 p[16], float u, float v) {
  vec4 bu = bsplineWeights(u), bv = bsplineWeights(v);
  vec3 pos = vec3(0.0f);
  for (int r = 0; r < 4; r++)
    pos += bv[r] * (bu[0] * p[4 * r] + bu[1] * p[4 * r + 1] + bu[2] * p[4 * r + 2] + bu[3] * p[4 * r + 3]);
  return pos;
}

// The limit point and limit normal of the ring's extraordinary vertex (Halstead et al. 1993).
VGEO_INLINE vec3 ringLimit(vec3 ring[VGEO_MAX_RING], int n, VGEO_OUT(vec3) normal) {
  float nn = float(n);
  float a = 1.0f + cos(6.28318531f / nn) + cos(3.14159265f / nn) * sqrt(2.0f * (9.0f + cos(6.28318531f / nn)));
  vec3 sumE = vec3(0.0f), sumF = vec3(0.0f), t1 = vec3(0.0f), t2 = vec3(0.0f);
  for (int j = 0; j < n; j++) {
    vec3 e = ring[1 + 2 * j], f = ring[2 + 2 * j];
    sumE += e;
    sumF += f;
    float c0 = cos(6.28318531f * float(j) / nn), c1 = cos(6.28318531f * float(j + 1) / nn);
    float s0 = sin(6.28318531f * float(j) / nn), s1 = sin(6.28318531f * float(j + 1) / nn);
    t1 += a * c0 * e + (c0 + c1) * f;
    t2 += a * s0 * e + (s0 + s1) * f;
  }
  normal = normalize(cross(t1, t2));
  return (nn * nn * ring[0] + 4.0f * sumE + sumF) / (nn * (nn + 5.0f));
}

// One Catmull-Clark round on the ring: the next ring (the sub-face at v) in `next`, and in `grid` the
// 5 x 5 chart of new points around the sub-faces, grid[5 (y + 1) + x + 1] for x, y in -1..3 (v at
// (0, 0), e_0 at (2, 0), e_1 at (0, 2), the patch the cell [0, 2]^2). The regular sub-patch of the
// cell with lower corner (cx, cy) has the control points grid(cx - 1 + c, cy - 1 + r).
VGEO_INLINE void subdivideRing(vec3 ring[VGEO_MAX_RING], int n, VGEO_OUT_ARRAY(vec3, next, VGEO_MAX_RING),
                               VGEO_OUT_ARRAY(vec3, grid, 25)) {
  // Face points of the sectors, then edge points of the spokes, then the vertex point.
  vec3 faceSum = vec3(0.0f), edgeSum = vec3(0.0f);
  for (int i = 0; i < n; i++) {
    next[2 + 2 * i] = 0.25f * (ring[0] + ring[1 + 2 * i] + ring[2 + 2 * i] + ring[1 + 2 * ((i + 1) % n)]);
    faceSum += next[2 + 2 * i];
    edgeSum += ring[1 + 2 * i];
  }
  for (int i = 0; i < n; i++)
    next[1 + 2 * i] = 0.25f * (ring[0] + ring[1 + 2 * i] + next[2 + 2 * i] + next[2 + 2 * ((i + n - 1) % n)]);
  float nn = float(n);
  // (Q + 2R + (n - 3) v) / n with Q the mean face point and R the mean spoke midpoint.
  next[0] = (faceSum / nn + (ring[0] + edgeSum / nn) + (nn - 3.0f) * ring[0]) / nn;
  vec3 v = ring[0], e0 = ring[1], f0 = ring[2], e1 = ring[3], f1 = ring[4];
  vec3 fLast = ring[2 * n], o0 = ring[2 * n + 1], o1 = ring[2 * n + 2], o2 = ring[2 * n + 3], o3 = ring[2 * n + 4];
  vec3 o4 = ring[2 * n + 5], o5 = ring[2 * n + 6], o6 = ring[2 * n + 7];
  vec3 face0 = next[2], face1 = next[4], faceLast = next[2 * n];
  // Face points of the outer cells: A right of the patch, B below A, C above A, D above the patch, E left of D.
  vec3 fA = 0.25f * (e0 + o1 + o2 + f0), fB = 0.25f * (e0 + fLast + o0 + o1), fC = 0.25f * (f0 + o2 + o3 + o4);
  vec3 fD = 0.25f * (e1 + f0 + o4 + o5), fE = 0.25f * (e1 + o5 + o6 + f1);
  // Vertex points of the regular corners e_0, f_0, e_1: (Q + 2R + v) / 4 over their four faces and edges.
  vec3 ve0 = ((faceLast + face0 + fA + fB) * 0.25f + (4.0f * e0 + v + f0 + o1 + fLast) * 0.25f + e0) * 0.25f;
  vec3 vf0 = ((face0 + fA + fC + fD) * 0.25f + (4.0f * f0 + e0 + o2 + o4 + e1) * 0.25f + f0) * 0.25f;
  vec3 ve1 = ((face0 + face1 + fD + fE) * 0.25f + (4.0f * e1 + v + f0 + o5 + f1) * 0.25f + e1) * 0.25f;
  grid[6] = next[0];                               // (0, 0)
  grid[7] = next[1];                               // (1, 0) = e'_0
  grid[11] = next[3];                              // (0, 1) = e'_1
  grid[12] = face0;                                // (1, 1)
  grid[1] = next[2 * n - 1];                       // (0, -1) = e'_(n-1)
  grid[2] = faceLast;                              // (1, -1)
  grid[5] = next[5];                               // (-1, 0) = e'_2
  grid[10] = face1;                                // (-1, 1)
  grid[3] = 0.25f * (e0 + fLast + faceLast + fB);  // (2, -1): edge e_0 f_(n-1)
  grid[8] = ve0;                                   // (2, 0)
  grid[13] = 0.25f * (e0 + f0 + face0 + fA);       // (2, 1): edge e_0 f_0
  grid[18] = vf0;                                  // (2, 2)
  grid[17] = 0.25f * (e1 + f0 + face0 + fD);       // (1, 2): edge e_1 f_0
  grid[16] = ve1;                                  // (0, 2)
  grid[15] = 0.25f * (e1 + f1 + face1 + fE);       // (-1, 2): edge e_1 f_1
  grid[4] = fB;                                    // (3, -1)
  grid[9] = 0.25f * (e0 + o1 + fA + fB);           // (3, 0): edge e_0 o_1
  grid[14] = fA;                                   // (3, 1)
  grid[19] = 0.25f * (f0 + o2 + fA + fC);          // (3, 2): edge f_0 o_2
  grid[24] = fC;                                   // (3, 3)
  grid[23] = 0.25f * (f0 + o4 + fC + fD);          // (2, 3): edge f_0 o_4
  grid[22] = fD;                                   // (1, 3)
  grid[21] = 0.25f * (e1 + o5 + fD + fE);          // (0, 3): edge e_1 o_5
  grid[20] = fE;                                   // (-1, 3)
  grid[0] = grid[6];                               // (-1, -1): not part of any sub-patch
  // The next ring's outer points: (2, -1), (2, 0), (2, 1), (2, 2), (1, 2), (0, 2), (-1, 2).
  next[2 * n + 1] = grid[3];
  next[2 * n + 2] = grid[8];
  next[2 * n + 3] = grid[13];
  next[2 * n + 4] = grid[18];
  next[2 * n + 5] = grid[17];
  next[2 * n + 6] = grid[16];
  next[2 * n + 7] = grid[15];
}

// For (a, b) with max(a, b) >= 1/2, from the chart `grid` of one subdivideRing round: the control points
// of the B-spline sub-patch of the cell (a, b) lies in, and (a, b) in the sub-patch's parameters.
VGEO_INLINE vec2 ringCell(vec3 grid[25], float a, float b, VGEO_OUT_ARRAY(vec3, sub, 16)) {
  int cx = a >= 0.5f ? 1 : 0, cy = b >= 0.5f ? 1 : 0;
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 4; c++) sub[4 * r + c] = grid[5 * (cy + r) + cx + c];
  return vec2(2.0f * a - float(cx), 2.0f * b - float(cy));
}

// The limit surface of a ring patch at (a, b) in [0, 1]^2, with its partial derivatives.
VGEO_INLINE vec3 evaluateRing(vec3 ring[VGEO_MAX_RING], int n, float a, float b, VGEO_OUT(vec3) da, VGEO_OUT(vec3) db) {
  vec3 cur[VGEO_MAX_RING];
  vec3 next[VGEO_MAX_RING];
  vec3 grid[25];
  vec3 sub[16];
  for (int i = 0; i < 2 * n + 8; i++) cur[i] = ring[i];
  float scale = 1.0f;
  for (int level = 0; level < 24; level++) {
    subdivideRing(cur, n, next, grid);
    if (max(a, b) >= 0.5f) {
      vec2 uv = ringCell(grid, a, b, sub);
      vec3 p = evaluateBspline(sub, uv.x, uv.y, da, db);
      da *= 2.0f * scale;
      db *= 2.0f * scale;
      return p;
    }
    for (int i = 0; i < 2 * n + 8; i++) cur[i] = next[i];
    a *= 2.0f;
    b *= 2.0f;
    scale *= 2.0f;
  }
  // Within 2^-24 of the vertex: its limit point, with tangents spanning its tangent plane.
  vec3 normal;
  vec3 p = ringLimit(ring, n, normal);
  da = normalize(cross(normal, cur[3] - cur[0]));
  db = cross(normal, da);
  return p;
}

// Face parameters (s, t) to the ring's (a, b) when the extraordinary vertex is corner `corner`: a runs
// towards the next corner, b towards the previous one (the same turn, so normals keep their side).
VGEO_INLINE vec2 ringParameters(uint corner, float s, float t) {
  if (corner == 0u) return vec2(s, t);
  if (corner == 1u) return vec2(t, 1.0f - s);
  if (corner == 2u) return vec2(1.0f - s, 1.0f - t);
  return vec2(1.0f - t, s);
}

// One step down a patch tree (shaderio.h, VGEO_PATCH_TREE): the quadrant of the face that (s, t) lies in,
// i.e. the sub-face at that corner after one Catmull-Clark round, and (s, t) in the sub-face's own
// parameters (its corner 0 is the face's corner, its corner 1 the midpoint of the edge that follows).
VGEO_INLINE uint patchQuadrant(VGEO_INOUT(vec2) st) {
  uint q = st.x >= 0.5f ? (st.y >= 0.5f ? 2u : 1u) : (st.y >= 0.5f ? 3u : 0u);
  st = 2.0f * ringParameters(q, st.x, st.y);
  return q;
}

// A patch (shaderio.h, Patch) of kind VGEO_PATCH_REGULAR, VGEO_PATCH_RING or VGEO_PATCH_NONE (bilinear
// between points 0..3, the corners in order) at face parameters (s, t), with its unit normal.
VGEO_INLINE vec3 evaluatePatch(uint kind, uint corner, int valence, vec3 points[VGEO_MAX_RING], float s, float t,
                               VGEO_OUT(vec3) normal) {
  vec3 du, dv, p;
  if (kind == VGEO_PATCH_REGULAR) {
    vec3 grid[16];
    for (int i = 0; i < 16; i++) grid[i] = points[i];
    p = evaluateBspline(grid, s, t, du, dv);
  } else if (kind == VGEO_PATCH_RING) {
    vec2 ab = ringParameters(corner, s, t);
    p = evaluateRing(points, valence, ab.x, ab.y, du, dv);
  } else {
    du = mix(points[1] - points[0], points[2] - points[3], t);
    dv = mix(points[3] - points[0], points[2] - points[1], s);
    p = mix(mix(points[0], points[1], s), mix(points[3], points[2], s), t);
  }
  normal = normalize(cross(du, dv));
  return p;
}

// Down a patch's tree (if any) to the leaf patch that holds st: returns the index of the leaf's first
// point word and sets info to its info word and st to its own parameters. `first` is the index of the
// patch's first word; child offsets count from it. The words are the C++ caller's array (of the patch's
// words, first 0) or the shaders' patchPoints.
#ifdef __cplusplus
#define VGEO_PATCH_WORDS_PARAM const uint *words,
#define VGEO_PATCH_WORD(i) words[i]
#else
#define VGEO_PATCH_WORDS_PARAM
#define VGEO_PATCH_WORD(i) patchPoints[i]
#endif
VGEO_INLINE uint patchLeaf(VGEO_PATCH_WORDS_PARAM uint first, VGEO_INOUT(uint) info, VGEO_INOUT(vec2) st) {
  uint at = first;
  for (int depth = 0; depth < VGEO_MAX_PATCH_DEPTH && patchKind(info) == VGEO_PATCH_TREE; depth++) {
    uint node = first + VGEO_PATCH_WORD(at + patchQuadrant(st));
    info = VGEO_PATCH_WORD(node);
    at = node + 1u;
  }
  return at;
}

#ifdef __cplusplus
// The C++ side of a patch's words (shaderio.h): `words` starts at the patch's firstPoint and holds `size`
// words; point(i) gives control point i (relative to pointBase). Tree walks stop at VGEO_MAX_PATCH_DEPTH.

// Calls visit(word index) for every control-point word of the patch (every node of a tree); false when
// the words are malformed (a node outside them, an unknown kind, a tree too deep).
template <class Visit>
bool forEachPatchPoint(uint info, const uint* words, size_t size, Visit visit, int depth = 0, size_t at = 0) {
  const uint kind = patchKind(info), valence = patchValence(info);
  if (kind == VGEO_PATCH_RING && (valence < 3u || valence > uint(VGEO_MAX_VALENCE))) return false;
  if (at > size || patchWordCount(info) > size - at) return false;
  if (kind != VGEO_PATCH_TREE) {
    for (uint i = 0; i < patchWordCount(info); i++) visit(at + i);
    return true;
  }
  if (depth >= VGEO_MAX_PATCH_DEPTH) return false;
  for (uint q = 0; q < 4u; q++) {
    size_t child = words[at + q];
    if (child <= at || child >= size) return false;  // children lie after their parent
    if (!forEachPatchPoint(words[child], words, size, visit, depth + 1, child + 1)) return false;
  }
  return true;
}

// The patch at (s, t) with its unit normal; a top-level VGEO_PATCH_NONE gives its corners as corner(k).
template <class Point, class Corner>
vec3 evaluatePatchWords(uint info, const uint* words, Point point, Corner corner, float s, float t, vec3& normal) {
  vec2 st(s, t);
  const uint at = patchLeaf(words, 0u, info, st);
  vec3 points[VGEO_MAX_RING];
  const bool flatFace = at == 0 && patchKind(info) == VGEO_PATCH_NONE;
  for (uint i = 0; i < patchWordCount(info); i++) points[i] = flatFace ? corner(i) : point(words[at + i]);
  return evaluatePatch(patchKind(info), patchCorner(info), int(patchValence(info)), points, st.x, st.y, normal);
}

// The patch's positions at `count` parameters, each the one evaluatePatchWords gives, in fewer steps:
// the samples on one leaf gather its points once, and the samples of a ring leaf share its rounds of
// subdivision (evaluateRing's loop run for all of them together), where one at a time repeats them.
// At most 32 samples.
template <class Point, class Corner>
void evaluatePatchWordsAt(uint info, const uint* words, Point point, Corner corner, const vec2* st, int count,
                          vec3* out) {
  constexpr int kMost = 32;
  uint leafAt[kMost], leafInfo[kMost];
  vec2 leafSt[kMost];
  bool done[kMost] = {};
  for (int i = 0; i < count; i++) {
    leafInfo[i] = info;
    leafSt[i] = st[i];
    leafAt[i] = patchLeaf(words, 0u, leafInfo[i], leafSt[i]);
  }
  vec3 points[VGEO_MAX_RING];
  for (int i = 0; i < count; i++) {
    if (done[i]) continue;
    const uint at = leafAt[i], kind = patchKind(leafInfo[i]), corner0 = patchCorner(leafInfo[i]);
    const int valence = int(patchValence(leafInfo[i]));
    const bool flatFace = at == 0 && kind == VGEO_PATCH_NONE;
    for (uint k = 0; k < patchWordCount(leafInfo[i]); k++) points[k] = flatFace ? corner(k) : point(words[at + k]);
    int group[kMost], size = 0;  // the samples on this leaf
    for (int j = i; j < count; j++)
      if (!done[j] && leafAt[j] == at) group[size++] = j, done[j] = true;
    vec3 normal, sub[16];
    if (kind == VGEO_PATCH_REGULAR) {
      // evaluateBsplinePosition's arithmetic, its four row sums made once for each distinct u.
      float rowU[kMost];
      vec3 rows[kMost][4];
      int rowCount = 0;
      for (int g = 0; g < size; g++) {
        const float u = leafSt[group[g]].x;
        int k = 0;
        while (k < rowCount && rowU[k] != u) k++;
        if (k == rowCount) {
          const vec4 bu = bsplineWeights(u);
          for (int r = 0; r < 4; r++)
            rows[k][r] = bu[0] * points[4 * r] + bu[1] * points[4 * r + 1] + bu[2] * points[4 * r + 2] +
                         bu[3] * points[4 * r + 3];
          rowU[rowCount++] = u;
        }
        const vec4 bv = bsplineWeights(leafSt[group[g]].y);
        vec3 pos = vec3(0.0f);
        for (int r = 0; r < 4; r++) pos += bv[r] * rows[k][r];
        out[group[g]] = pos;
      }
      continue;
    }
    if (kind != VGEO_PATCH_RING) {
      for (int g = 0; g < size; g++)
        out[group[g]] = evaluatePatch(kind, corner0, valence, points, leafSt[group[g]].x, leafSt[group[g]].y, normal);
      continue;
    }
    vec2 ab[kMost];
    for (int g = 0; g < size; g++) ab[g] = ringParameters(corner0, leafSt[group[g]].x, leafSt[group[g]].y);
    vec3 cur[VGEO_MAX_RING], next[VGEO_MAX_RING], grid[25];
    for (int k = 0; k < 2 * valence + 8; k++) cur[k] = points[k];
    int left = size;
    for (int level = 0; level < 24 && left > 0; level++) {
      subdivideRing(cur, valence, next, grid);
      for (int g = 0; g < size; g++) {
        if (group[g] < 0) continue;
        if (max(ab[g].x, ab[g].y) >= 0.5f) {
          const vec2 uv = ringCell(grid, ab[g].x, ab[g].y, sub);
          out[group[g]] = evaluateBsplinePosition(sub, uv.x, uv.y);
          group[g] = -1;
          left--;
        } else {
          ab[g] *= 2.0f;
        }
      }
      for (int k = 0; k < 2 * valence + 8; k++) cur[k] = next[k];
    }
    for (int g = 0; g < size; g++)
      if (group[g] >= 0) out[group[g]] = ringLimit(points, valence, normal);
  }
}
#endif

VGEO_NAMESPACE_END

#endif
