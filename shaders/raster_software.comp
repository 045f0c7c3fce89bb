#version 450
// raster_software.comp: one thread a triangle that triangle culling binned to software (listed from the
// end of the triangle list), drawn into the visibility buffer (raster_triangle.glsl) under the id of its
// triangle-list word.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "raster_setup.glsl"
#include "visibility.glsl"
#include "raster_triangle.glsl"
layout(local_size_x = 64) in;

void main() {
  uint k = (gl_WorkGroupID.y * 65535u + gl_WorkGroupID.x) * 64u + gl_LocalInvocationIndex;
  if (k >= min(counters.softwareTriangles, frame.triangleCapacity)) return;
  uint word = triangleList[frame.triangleCapacity - 1u - k];
  uint entry = word >> VGEO_TRIANGLE_BITS, triangle = word & ((1u << VGEO_TRIANGLE_BITS) - 1u);
  Instance inst = instances[drawList[2u * entry]];
  Cluster c = clusters[drawList[2u * entry + 1u] & ~VGEO_DRAW_PATCHES_BIT];
  i64vec2 v[3];
  float z[3];
  for (uint i = 0u; i < 3u; i++) {
    vec4 clip = clipPosition(inst, vertexPosition(triangleVertex(c, triangle, i)));
    v[i] = i64vec2(round(screenPosition(clip) * VGEO_SUBPIXEL_SCALE));
    z[i] = clip.z / clip.w;
  }
  rasterTriangle(v, z, uint64_t(word));
}
