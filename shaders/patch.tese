#version 450
// patch.tese: a vertex of a tessellated cage face on the limit surface, by the rules of
// patch_surface.glsl (corners, edge points, inner points), so that it meets its neighbours without a gap
// whichever path draws them.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "patch_surface.glsl"
#include "shade.glsl"

layout(quads, equal_spacing, cw) in;  // cw: with the upper-left domain origin, front faces stay front
layout(location = 0) patch in uvec4 pIds;  // face, instance, cluster, level-0 group

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec3 outBarycentric;
layout(location = 2) flat out uvec4 outIds;   // cluster, group, instance, level
layout(location = 4) flat out uint outTriangle;
layout(location = 3) flat out vec2 outInfo;   // patch mode: log2(largest factor) / 6 (1 -> 0, 64 -> 1)

void main() {
  uint face = pIds.x;
  Instance inst = instances[pIds.y];
  float s = gl_TessCoord.x, t = gl_TessCoord.y;
  bool onS = s == 0.0 || s == 1.0, onT = t == 0.0 || t == 1.0;
  vec3 position, normal;
  if (onS && onT) {
    position = cornerPoint(face, s == 0.0 ? (t == 0.0 ? 0u : 3u) : (t == 0.0 ? 1u : 2u), normal);
  } else if (onS || onT) {
    // Edge k and the integer step along it (outer levels: u = 0, v = 0, u = 1, v = 1).
    uint k = t == 0.0 ? 0u : s == 1.0 ? 1u : t == 1.0 ? 2u : 3u;
    float along = k == 0u ? s : k == 1u ? t : k == 2u ? 1.0 - s : 1.0 - t;
    uint n = uint(gl_TessLevelOuter[k == 0u ? 1u : k == 1u ? 2u : k == 2u ? 3u : 0u] + 0.5);
    position = edgePoint(face, k, uint(along * float(n) + 0.5), n, normal);
  } else {
    position = evaluateFace(face, vec2(s, t), normal);
  }
  gl_Position = clipPosition(inst, position);
  outNormal = normalToWorld(inst, normal);
  outBarycentric = vec3(1.0);
  Cluster c = clusters[pIds.z];
  outIds = uvec4(pIds.z, pIds.w, pIds.y, clusterLevel(c.counts));
  outTriangle = 0u;
  float largest = max(max(gl_TessLevelOuter[0], gl_TessLevelOuter[1]), max(max(gl_TessLevelOuter[2], gl_TessLevelOuter[3]),
                      max(gl_TessLevelInner[0], gl_TessLevelInner[1])));
  outInfo = patchViewInfo(inst, c, largest);
}
