#version 450
// finalize_triangles.comp: one thread, after triangle culling: the overflow of the triangle list (its
// hardware part from the start and its software part from the end met), the indirect draw of the listed
// hardware triangles as instances of 128 triangles (draw.vert), the software rasterizer's dispatch
// (raster_software.comp, 64 triangles a workgroup), and for the patch list the same: its overflow, the
// tessellated draw of its hardware part, one vertex (patch) each (patch.tesc), and the dispatch of
// raster_patches.comp, a workgroup a patch of its software part.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 1) in;
#include "common.glsl"

void main() {
  uint hardware = counters.hardwareTriangles, software = counters.softwareTriangles;
  // Summed over the passes of a frame with occlusion culling (the late one lists its own from the start).
  counters.trianglesDrawn += hardware + software;
  if (hardware + software > frame.triangleCapacity) counters.triangleOverflow += hardware + software - frame.triangleCapacity;
  uint listed = min(hardware, frame.triangleCapacity);
  uint workgroups = (min(software, frame.triangleCapacity) + 63u) / 64u;
  counters.rasterDispatch[0] = min(workgroups, 65535u);
  counters.rasterDispatch[1] = (workgroups + 65534u) / 65535u;
  counters.rasterDispatch[2] = 1u;
  counters.rasterDispatch[3] = 0u;
  counters.draw[0] = 3u * VGEO_MAX_CLUSTER_TRIANGLES;
  counters.draw[1] = (listed + VGEO_MAX_CLUSTER_TRIANGLES - 1u) / VGEO_MAX_CLUSTER_TRIANGLES;
  counters.draw[2] = 0u;
  counters.draw[3] = 0u;
  uint hardwarePatches = counters.hardwarePatches, softwarePatches = counters.softwarePatches;
  counters.patchesDrawn = hardwarePatches + softwarePatches;
  if (hardwarePatches + softwarePatches > frame.patchCapacity)
    counters.patchOverflow = hardwarePatches + softwarePatches - frame.patchCapacity;
  uint patchCount = min(hardwarePatches, frame.patchCapacity);
  counters.patchDraw[0] = frame.patchesPerInstance;
  counters.patchDraw[1] = (patchCount + frame.patchesPerInstance - 1u) / frame.patchesPerInstance;
  counters.patchDraw[2] = 0u;
  counters.patchDraw[3] = 0u;
  // raster_patches.comp: a workgroup a compute patch, then one a grid for the hardware.
  uint patchGroups = min(softwarePatches, frame.patchCapacity) + (frame.softwarePatches != 0u ? patchCount : 0u);
  counters.patchRasterDispatch[0] = min(patchGroups, 65535u);
  counters.patchRasterDispatch[1] = (patchGroups + 65534u) / 65535u;
  counters.patchRasterDispatch[2] = 1u;
  counters.patchRasterDispatch[3] = 0u;
}
