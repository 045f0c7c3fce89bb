#version 450
// patch.tese: a vertex of a tessellated cage face on the limit surface (patch_eval.h). Three kinds of
// vertex, so that neighbours produce the same bits where they meet:
//   - a corner is the face's leaf vertex, as draw.vert draws it (a patch-drawn cluster meets a
//     triangle-drawn one there without a gap);
//   - a vertex inside an edge is evaluated on whichever of the edge's two faces has the lower index,
//     at i / factor along that face's edge (i counted from its end), so both sides run the same
//     arithmetic on the same data;
//   - any other vertex is evaluated on its own face.
// A flat face (VGEO_PATCH_NONE) is bilinear between its corners; all its edges are at factor 1. A tree
// (VGEO_PATCH_TREE) is walked down to the patch of the quadrant the vertex lies in.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "patch_eval.h"

layout(quads, equal_spacing, cw) in;  // cw: with the upper-left domain origin, front faces stay front
layout(location = 0) patch in uvec4 pIds;  // face, instance, cluster, level-0 group

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec3 outBarycentric;
layout(location = 2) flat out uvec4 outIds;   // cluster, group, instance, level
layout(location = 4) flat out uint outTriangle;
layout(location = 3) flat out vec2 outInfo;   // patch mode: log2(largest factor) / 6 (1 -> 0, 64 -> 1)

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

void main() {
  uint face = pIds.x;
  Instance inst = instances[pIds.y];
  float s = gl_TessCoord.x, t = gl_TessCoord.y;
  bool onS = s == 0.0 || s == 1.0, onT = t == 0.0 || t == 1.0;
  vec3 position, normal;
  if (onS && onT) {
    uint k = s == 0.0 ? (t == 0.0 ? 0u : 3u) : (t == 0.0 ? 1u : 2u);
    uint vertex = cageFaceVertices[cageFaces[face].firstVertex + k];
    position = vertexPosition(vertex);
    normal = decodeNormal(normals[vertex]);
  } else {
    uint evalFace = face;
    vec2 st = vec2(s, t);
    if (onS || onT) {
      // Edge k and the integer step along it (outer levels: u = 0, v = 0, u = 1, v = 1).
      uint k = t == 0.0 ? 0u : s == 1.0 ? 1u : t == 1.0 ? 2u : 3u;
      float along = k == 0u ? s : k == 1u ? t : k == 2u ? 1.0 - s : 1.0 - t;
      uint n = uint(gl_TessLevelOuter[k == 0u ? 1u : k == 1u ? 2u : k == 2u ? 3u : 0u] + 0.5);
      uint i = uint(along * float(n) + 0.5);
      uint other = patches[face].neighbours[k];
      if (other != VGEO_INVALID && (other >> 2u) < face) {
        evalFace = other >> 2u;
        st = onEdge(other & 3u, n - i, n);
      } else {
        st = onEdge(k, i, n);
      }
    }
    position = evaluateFace(evalFace, st, normal);
  }
  gl_Position = clipPosition(inst, position);
  outNormal = normalToWorld(inst, normal);
  outBarycentric = vec3(1.0);
  Cluster c = clusters[pIds.z];
  outIds = uvec4(pIds.z, pIds.w, pIds.y, clusterLevel(c.counts));
  outTriangle = 0u;
  float largest = max(max(gl_TessLevelOuter[0], gl_TessLevelOuter[1]), max(max(gl_TessLevelOuter[2], gl_TessLevelOuter[3]),
                      max(gl_TessLevelInner[0], gl_TessLevelInner[1])));
  outInfo = vec2(frame.mode == VGEO_MODE_PATCH ? log2(largest) / 6.0 : projectedErrorWorld(inst, c.selfSphere, c.selfError) / frame.tau, 0.0);
}
