#version 450
// cull_triangles.comp: one workgroup a draw-list entry, one thread a triangle of its cluster. A triangle
// joins the triangle list unless the draw camera cannot see it (Wihlidal, "Optimizing the Graphics
// Pipeline with Compute", GDC 2016):
//   - all three corners beyond one plane of the view volume (left, right, top, bottom, near);
//   - facing away from the eye on a closed, outward-facing instance (the front side hides it);
//   - its screen bounding box holds no pixel centre, so it makes no fragment.
// A leaf cluster flagged for patches (VGEO_DRAW_PATCHES_BIT) is left to cull_patches.comp: its entry
// joins the patch-entry list, which a pass of its own goes through (lavapipe runs every line of a
// shader whatever its lanes branch to, docs/gpu-notes.md 17: here every cluster paid for the patch code).
// A triangle that stays is binned: to the hardware draw (listed from the triangle list's start) or, when
// all its corners are in front of the near plane and it is small on screen (raster_setup.glsl), to the
// software rasterizer (listed from the end, raster_software.comp). finalize_triangles.comp counts an
// overflow when the two meet.
// None of these changes the picture: they keep the rasterizer from setting up triangles that make no
// fragment, which is where the time of a virtual-geometry frame goes once clusters are small on
// screen (docs/gpu-notes.md, 6 and 10). The cut itself (the draw list) is untouched.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "raster_setup.glsl"
layout(local_size_x = VGEO_MAX_CLUSTER_TRIANGLES) in;
#include "cull_triangles.glsl"

void main() {
  uint entry = counters.drawBase + gl_WorkGroupID.y * 65535u + gl_WorkGroupID.x;  // this pass's entries
  if (entry >= min(counters.drawCount, frame.drawCapacity)) return;  // the whole workgroup
  if (gl_LocalInvocationIndex == 0u) {
    sKeptTriangles = 0u;
    sSoftware = 0u;
  }
  barrier();
  uint instance = drawList[2u * entry], cluster = drawList[2u * entry + 1u];
  if ((cluster & VGEO_DRAW_PATCHES_BIT) != 0u) {  // the same for the whole workgroup
    if (gl_LocalInvocationIndex == 0u) patchEntries[atomicAdd(counters.patchEntries, 1u)] = entry;
    return;
  }
  Cluster c = clusters[cluster];
  uint triangle = gl_LocalInvocationIndex;
  uint bins[2] = uint[2](triangle < clusterTriangleCount(c.counts) ? binTriangle(instances[instance], c, triangle) : kCulled, kCulled);
  listTriangles(entry, triangle, bins);
}
