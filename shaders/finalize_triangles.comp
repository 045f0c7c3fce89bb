#version 450
// finalize_triangles.comp: one thread, after triangle culling: the indirect draw of the listed
// triangles (never more than the triangle list holds) as instances of 128 triangles (draw.vert), and
// the tessellated draw of the listed patches, one vertex (patch) each (patch.tesc).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 1) in;
#include "common.glsl"

void main() {
  uint listed = min(counters.trianglesDrawn, frame.triangleCapacity);
  counters.draw[0] = 3u * VGEO_MAX_CLUSTER_TRIANGLES;
  counters.draw[1] = (listed + VGEO_MAX_CLUSTER_TRIANGLES - 1u) / VGEO_MAX_CLUSTER_TRIANGLES;
  counters.draw[2] = 0u;
  counters.draw[3] = 0u;
  uint patchCount = min(counters.patchesDrawn, frame.patchCapacity);
  counters.patchDraw[0] = frame.patchesPerInstance;
  counters.patchDraw[1] = (patchCount + frame.patchesPerInstance - 1u) / frame.patchesPerInstance;
  counters.patchDraw[2] = 0u;
  counters.patchDraw[3] = 0u;
}
