#version 450
// draw.vert: corner gl_VertexIndex % 3 of a triangle of a draw-list entry, which names (instance, cluster).
// One draw of 384-vertex instances (docs/gpu-notes.md, 14: never one huge vertex count).
// With triangle culling (the default), instance i draws triangles 128 i .. 128 i + 127 of the triangle
// list, each naming its entry and triangle; without, instance i is draw-list entry i and vertex / 3 the
// cluster's triangle. Slots past the end collapse to a point outside the clip volume.
// Built with VGEO_VISIBILITY_ONLY for the bare render pass (draw_visibility.frag): the position and the
// triangle's word only.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "raster_setup.glsl"
#include "shade.glsl"

#ifdef VGEO_VISIBILITY_ONLY
layout(location = 5) flat out uvec2 outId;  // visibility id: (entry << VGEO_TRIANGLE_BITS | triangle, 0)
#else
layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec3 outBarycentric;
layout(location = 2) flat out uvec4 outIds;   // cluster, group, instance, level
layout(location = 4) flat out uint outTriangle;
layout(location = 3) flat out vec2 outInfo;   // projected self error / tau; frozen-diff state
#endif

void main() {
  uint entry = uint(gl_InstanceIndex), triangle = uint(gl_VertexIndex) / 3u, corner = uint(gl_VertexIndex) % 3u;
  if (frame.triangleCull != 0u) {
    uint slot = uint(gl_InstanceIndex) * VGEO_MAX_CLUSTER_TRIANGLES + triangle;
    if (slot >= min(counters.hardwareTriangles, frame.triangleCapacity)) {
      gl_Position = vec4(0.0, 0.0, 2.0, 1.0);
      return;
    }
    uint packed = triangleList[slot];
    entry = packed >> VGEO_TRIANGLE_BITS;
    triangle = packed & ((1u << VGEO_TRIANGLE_BITS) - 1u);
  }
  uint instance = drawList[2 * entry];
  // A patch-drawn cluster lists the triangles of its faces that need no tessellation (cull_triangles.comp).
  uint cluster = drawList[2 * entry + 1] & ~VGEO_DRAW_PATCHES_BIT;
  Cluster c = clusters[cluster];
#ifdef VGEO_VISIBILITY_ONLY
  outId = uvec2(entry << VGEO_TRIANGLE_BITS | triangle, 0u);
#else
  outBarycentric = vec3(corner == 0u ? 1.0 : 0.0, corner == 1u ? 1.0 : 0.0, corner == 2u ? 1.0 : 0.0);
  outIds = uvec4(cluster, c.group, instance, clusterLevel(c.counts));
  outTriangle = triangle;
#endif
  if (triangle >= clusterTriangleCount(c.counts)) {
    gl_Position = vec4(0.0, 0.0, 2.0, 1.0);
#ifndef VGEO_VISIBILITY_ONLY
    outNormal = vec3(0.0);
    outInfo = vec2(0.0);
#endif
    return;
  }
  uint vertex = triangleVertex(c, triangle, corner);
  Instance inst = instances[instance];
  gl_Position = clipPosition(inst, vertexPosition(vertex));
#ifndef VGEO_VISIBILITY_ONLY
  outNormal = normalToWorld(inst, decodeNormal(normals[vertex]));
  outInfo = clusterViewInfo(inst, c);
#endif
}
