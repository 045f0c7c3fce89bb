// patch_surface.glsl: the points of a tessellated cage face on the limit surface (patch_eval.h), as both
// patch paths make them: the hardware tessellator's (patch.tese) and the compute rasterizer's grid
// (raster_patches.comp, resolve.comp). Three kinds of point, so that neighbours produce the same bits
// where they meet, whichever path draws each:
//   - a corner is the face's leaf vertex, as draw.vert draws it (a patch-drawn cluster meets a
//     triangle-drawn one there without a gap);
//   - a point inside an edge is evaluated on whichever of the edge's two faces has the lower index, at
//     i / factor along that face's edge (i counted from its end), so both sides run the same arithmetic
//     on the same data;
//   - any other point is evaluated on its own face.
// A flat face (VGEO_PATCH_NONE) is bilinear between its corners; all its edges are at factor 1. A tree
// (VGEO_PATCH_TREE) is walked down to the patch of the quadrant the point lies in. Needs common.glsl.
#include "patch_eval.h"

// Face parameters of the point i / n along edge k (from corner k to corner k + 1).
vec2 onEdge(uint k, uint i, uint n) {
  float t = float(i) / float(n), r = float(n - i) / float(n);
  return k == 0u ? vec2(t, 0.0) : k == 1u ? vec2(1.0, t) : k == 2u ? vec2(r, 1.0) : vec2(0.0, r);
}

// Face `face`'s patch at st: down its tree (if any) to a B-spline, ring or bilinear patch.
vec3 evaluateFace(uint face, vec2 st, out vec3 normal) {
  Patch p = patches[face];
  uint info = p.info;
  uint at = patchLeaf(p.firstPoint, info, st);
  vec3 points[VGEO_MAX_RING];
  uint count = patchWordCount(info);
  bool flatFace = patchKind(p.info) == VGEO_PATCH_NONE;
  for (uint i = 0u; i < count; i++) {
    uint v = flatFace ? cageFaceVertices[cageFaces[face].firstVertex + i] : p.pointBase + patchPoints[at + i];
    points[i] = flatFace ? vertexPosition(v) : vec3(controlPoints[3u * v], controlPoints[3u * v + 1u], controlPoints[3u * v + 2u]);
  }
  return evaluatePatch(patchKind(info), patchCorner(info), int(patchValence(info)), points, st.x, st.y, normal);
}

// Corner k of the face (0: (0, 0), 1: (1, 0), 2: (1, 1), 3: (0, 1)): its leaf vertex.
vec3 cornerPoint(uint face, uint k, out vec3 normal) {
  uint vertex = cageFaceVertices[cageFaces[face].firstVertex + k];
  normal = decodeNormal(normals[vertex]);
  return vertexPosition(vertex);
}

// Where the point i / n along edge k of the face (0 < i < n) is evaluated: on the face of the edge
// with the lower index, at those parameters.
void edgeParameters(inout uint face, uint k, uint i, uint n, out vec2 st) {
  uint other = patches[face].neighbours[k];
  if (other != VGEO_INVALID && (other >> 2u) < face) {
    face = other >> 2u;
    st = onEdge(other & 3u, n - i, n);
  } else {
    st = onEdge(k, i, n);
  }
}

// The point i / n along edge k of the face (0 < i < n).
vec3 edgePoint(uint face, uint k, uint i, uint n, out vec3 normal) {
  vec2 st;
  edgeParameters(face, k, i, n, st);
  return evaluateFace(face, st, normal);
}

// The compute path's tessellation of a face: a grid of inner[0] x inner[1] cells, two triangles a cell,
// whose boundary points move along their edge to the nearest of the edge's factor + 1 points (each inner
// factor is at least its edges', so every edge point is reached and the boundary is exactly the edge's
// segments, as the neighbour and the hardware path cut it; cells that lose a side make empty triangles).
// Grid point (i, j), 0 <= i <= cells.x, 0 <= j <= cells.y, of a face with edge factors `edges`: one
// evaluation at most (one call site: the evaluation is most of a rasterizer's code).
vec3 gridPoint(uint face, uvec2 cells, uvec4 edges, uint i, uint j, out vec3 normal) {
  // On the boundary: edge k, step `at` of n along it, round(a * n / b) for grid step a of b.
  uint k = 4u, a = 0u, b = 1u, n = 1u;
  if (j == 0u) { k = 0u; a = i; b = cells.x; n = edges.x; }
  else if (i == cells.x) { k = 1u; a = j; b = cells.y; n = edges.y; }
  else if (j == cells.y) { k = 2u; a = cells.x - i; b = cells.x; n = edges.z; }
  else if (i == 0u) { k = 3u; a = cells.y - j; b = cells.y; n = edges.w; }
  uint at = (2u * a * n + b) / (2u * b);
  if (k < 4u && (at == 0u || at == n)) return cornerPoint(face, at == 0u ? k : (k + 1u) % 4u, normal);
  vec2 st = vec2(float(i) / float(cells.x), float(j) / float(cells.y));
  if (k < 4u) edgeParameters(face, k, at, n, st);
  return evaluateFace(face, st, normal);
}

// A grid point's record in the patch grid (shaderio_frame.h): the normal octahedral, as the normals
// section's (vgeo_file.h, encodeNormal), so that decodeNormal reads it.
vec4 gridRecord(vec3 position, vec3 normal) {
  vec3 n = normal / (abs(normal.x) + abs(normal.y) + abs(normal.z) + 1e-30);
  vec2 e = n.z < 0.0 ? (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0) : n.xy;
  return vec4(position, uintBitsToFloat(packSnorm2x16(e)));
}

// The patch-list grid word of a grid of `cells` cells whose first point is at `offset`.
uint gridWord(uint offset, uvec2 cells) {
  return offset | (cells.x - 1u) << VGEO_PATCH_GRID_OFFSET_BITS | (cells.y - 1u) << (VGEO_PATCH_GRID_OFFSET_BITS + 6u);
}
uint gridOffset(uint word) { return word & ((1u << VGEO_PATCH_GRID_OFFSET_BITS) - 1u); }
uvec2 gridCells(uint word) { return uvec2(word >> VGEO_PATCH_GRID_OFFSET_BITS, word >> (VGEO_PATCH_GRID_OFFSET_BITS + 6u)) % 64u + 1u; }

// Grid point k (0..2) of triangle t of the grid: cell t / 2 row by row, split along the diagonal from
// its (0, 0) to its (1, 1) corner.
uvec2 gridTriangleCorner(uvec2 cells, uint t, uint k) {
  uint cell = t >> 1u;
  uvec2 at = uvec2(cell % cells.x, cell / cells.x);
  uvec2 lower[3] = uvec2[3](uvec2(0u, 0u), uvec2(1u, 0u), uvec2(1u, 1u));
  uvec2 upper[3] = uvec2[3](uvec2(0u, 0u), uvec2(1u, 1u), uvec2(0u, 1u));
  return at + ((t & 1u) == 0u ? lower[k] : upper[k]);
}
