#version 450
// raster_patches.comp: one workgroup a patch that patch culling gave the compute rasterizer (listed from
// the end of the patch list): its face tessellated at the factors of patch_factors.glsl into the grid
// of patch_surface.glsl, whose micro-triangles go into the visibility buffer (raster_triangle.glsl)
// under the id of (patch-list slot, triangle), and whose points go into the patch grid for the resolve
// (at the place patch culling reserved). The grid is walked in tiles of VGEO_PATCH_TILE x
// VGEO_PATCH_TILE cells: the tile's points are evaluated once each on the limit surface into shared
// memory, projected and snapped, then each thread draws a triangle of the tile. Points the neighbouring
// face shares are evaluated by the same rule there (patch_surface.glsl), so the two meet without a gap.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "patch_factors.glsl"
#include "patch_surface.glsl"
#include "raster_setup.glsl"
#include "visibility.glsl"
#include "raster_triangle.glsl"

const uint kTilePoints = (VGEO_PATCH_TILE + 1u) * (VGEO_PATCH_TILE + 1u);
layout(local_size_x = 2u * VGEO_PATCH_TILE * VGEO_PATCH_TILE) in;

shared ivec2 sScreen[kTilePoints];  // snapped, 1/VGEO_SUBPIXEL_SCALE pixels
shared float sDepth[kTilePoints];

void main() {
  // Workgroups first for the compute rasterizer's patches (from the list's end), then for the hardware's
  // (from its start), whose grids are only evaluated: patch_grid.vert draws them.
  uint index = gl_WorkGroupID.y * 65535u + gl_WorkGroupID.x;
  uint software = min(counters.softwarePatches, frame.patchCapacity);
  bool rasterize = index < software;
  if (!rasterize && index - software >= min(counters.hardwarePatches, frame.patchCapacity)) return;  // the whole workgroup
  uint slot = rasterize ? frame.patchCapacity - 1u - index : index - software;
  uint word = patchList[2u * slot], grid = patchList[2u * slot + 1u];
  uint entry = word >> VGEO_TRIANGLE_BITS, local = word & ((1u << VGEO_TRIANGLE_BITS) - 1u);
  Instance inst = instances[drawList[2u * entry]];
  Cluster c = clusters[drawList[2u * entry + 1u] & ~VGEO_DRAW_PATCHES_BIT];
  uint face = c.cageFaceOffset + local;
  float edge[4], inner[2];
  patchFactors(inst, face, edge, inner);
  uvec2 cells = gridCells(grid);
  uvec4 edges = uvec4(edge[0], edge[1], edge[2], edge[3]);
  if (gl_LocalInvocationIndex == 0u) atomicAdd(counters.softwarePatchTriangles, 2u * cells.x * cells.y);
  if (!rasterize) {  // evaluate the grid points only, each once; patch_grid.vert draws its triangles
    if (gl_LocalInvocationIndex == 0u) patchDraws[slot] = uvec4(6u * cells.x * cells.y, 1u, 0u, slot);
    uint points = (cells.x + 1u) * (cells.y + 1u);
    for (uint k = gl_LocalInvocationIndex; k < points; k += gl_WorkGroupSize.x) {
      vec3 normal;
      uvec2 at = uvec2(k % (cells.x + 1u), k / (cells.x + 1u));
      vec3 p = gridPoint(face, cells, edges, at.x, at.y, normal);
      patchGrid[gridOffset(grid) + at.y * (cells.x + 1u) + at.x] = gridRecord(p, normal);
    }
    return;
  }
  uvec2 tiles = (cells + VGEO_PATCH_TILE - 1u) / VGEO_PATCH_TILE;
  for (uint tile = 0u; tile < tiles.x * tiles.y; tile++) {
    uvec2 origin = uvec2(tile % tiles.x, tile / tiles.x) * VGEO_PATCH_TILE;
    uvec2 size = min(cells - origin, uvec2(VGEO_PATCH_TILE));
    uint k = gl_LocalInvocationIndex;
    if (k < (size.x + 1u) * (size.y + 1u)) {
      vec3 normal;
      uvec2 at = origin + uvec2(k % (size.x + 1u), k / (size.x + 1u));
      vec3 p = gridPoint(face, cells, edges, at.x, at.y, normal);
      patchGrid[gridOffset(grid) + at.y * (cells.x + 1u) + at.x] = gridRecord(p, normal);
      vec4 clip = clipPosition(inst, p);
      sScreen[k] = ivec2(round(screenPosition(clip) * VGEO_SUBPIXEL_SCALE));
      sDepth[k] = clip.z / clip.w;
    }
    barrier();
    if (k < 2u * size.x * size.y) {
      uvec2 cell = origin + uvec2((k >> 1u) % size.x, (k >> 1u) / size.x);
      uint triangle = 2u * (cell.y * cells.x + cell.x) + (k & 1u);
      i64vec2 v[3];
      float z[3];
      for (uint i = 0u; i < 3u; i++) {
        uvec2 at = gridTriangleCorner(cells, triangle, i) - origin;
        uint point = at.y * (size.x + 1u) + at.x;
        v[i] = i64vec2(sScreen[point]);
        z[i] = sDepth[point];
      }
      rasterTriangle(v, z, patchTriangleId(slot, triangle));
    }
    barrier();
  }
}
