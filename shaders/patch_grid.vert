#version 450
// patch_grid.vert: corner gl_VertexIndex % 3 of triangle gl_VertexIndex / 3 of the grid of the patch in
// slot gl_InstanceIndex of the patch list's hardware part, in frames with patches in compute: the patches
// the compute rasterizer does not take (they reach the near plane, or their cells are large on screen)
// are drawn by the hardware from the grid raster_patches.comp evaluated, with the same ids, so one
// resolve shades both. One draw a patch, of its grid's vertex count (patchDraws, vkCmdDrawIndirectCount).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "patch_surface.glsl"

layout(location = 5) flat out uvec2 outId;  // visibility id, low word first (visibility.glsl)

void main() {
  uint slot = uint(gl_InstanceIndex), triangle = uint(gl_VertexIndex) / 3u;
  uint grid = patchList[2u * slot + 1u];
  uvec2 cells = gridCells(grid);
  uint entry = patchList[2u * slot] >> VGEO_TRIANGLE_BITS;
  Instance inst = instances[drawList[2u * entry]];
  uvec2 at = gridTriangleCorner(cells, triangle, uint(gl_VertexIndex) % 3u);
  gl_Position = clipPosition(inst, patchGrid[gridOffset(grid) + at.y * (cells.x + 1u) + at.x].xyz);
  // VGEO_VISIBILITY_PATCH_BIT | slot << VGEO_PATCH_TRIANGLE_BITS | triangle, in two words.
  outId = uvec2(slot << VGEO_PATCH_TRIANGLE_BITS | triangle, (slot >> (32u - VGEO_PATCH_TRIANGLE_BITS)) | 2u);
}
