#version 450
// patch.tesc: tessellation factors of one listed patch (a cage face of a leaf cluster drawn as patches),
// from patch_factors.glsl, which cull_triangles.comp shares to send faces that need no tessellation to
// the triangle list instead.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "patch_factors.glsl"

layout(vertices = 1) out;
layout(location = 0) in uint vPatch[];     // the patch's index in the patch list (patch.vert)
layout(location = 0) patch out uvec4 pIds;  // face, instance, cluster, level-0 group

void main() {
  if (vPatch[0] >= min(counters.hardwarePatches, frame.patchCapacity)) {  // past the list in the last instance
    gl_TessLevelOuter[0] = 0.0;  // a zero outer level discards the patch
    gl_TessLevelOuter[1] = 0.0;
    gl_TessLevelOuter[2] = 0.0;
    gl_TessLevelOuter[3] = 0.0;
    return;
  }
  uint packed = patchList[2u * vPatch[0]];
  uint entry = packed >> VGEO_TRIANGLE_BITS, local = packed & ((1u << VGEO_TRIANGLE_BITS) - 1u);
  uint instance = drawList[2u * entry], cluster = drawList[2u * entry + 1u] & ~VGEO_DRAW_PATCHES_BIT;
  Cluster c = clusters[cluster];
  uint face = c.cageFaceOffset + local;
  float edge[4], inner[2];
  patchFactors(instances[instance], face, edge, inner);
  // Outer levels are ordered u = 0, v = 0, u = 1, v = 1.
  gl_TessLevelOuter[0] = edge[3];
  gl_TessLevelOuter[1] = edge[0];
  gl_TessLevelOuter[2] = edge[1];
  gl_TessLevelOuter[3] = edge[2];
  gl_TessLevelInner[0] = inner[0];
  gl_TessLevelInner[1] = inner[1];
  pIds = uvec4(face, instance, cluster, c.group);
}
