#version 450
// cull_patches.comp: one workgroup a patch-drawn leaf cluster (the patch-entry list of
// cull_triangles.comp), one thread a cage face. A face joins the patch list unless its bounding sphere
// (its corners, grown by its chord error: the surface is that close to its triangles) is outside the
// frustum: from the list's end for the compute rasterizer (raster_patches.comp) when it takes the face
// (in front of the near plane and its grid cells small on screen), else from its start for the
// hardware: drawn from its grid (patch_grid.vert) when the frame has patches in compute, else by the
// tessellator (patch.tesc). finalize_triangles.comp counts an overflow when the two meet. With patches
// in compute each listed face reserves its grid's points in the patch grid; a face whose grid does not
// fit is drawn as its leaf triangles. A face whose tessellation factors are all 1 (patch_factors.glsl:
// small on screen, or flat enough) would be drawn as its two corner triangles anyway: its leaf
// triangles join the triangle list instead (binned as cull_triangles.comp bins), so the patch list
// holds only faces that gain from tessellation.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "patch_factors.glsl"
#include "patch_surface.glsl"
#include "raster_setup.glsl"
layout(local_size_x = VGEO_MAX_CLUSTER_TRIANGLES) in;
#include "cull_triangles.glsl"

shared uint sHardware, sBaseHardware, sSoftwarePatches, sBaseSoftwarePatches, sGridPoints, sBaseGridPoints;

// The sphere around face `face`'s corners (world space), grown by its chord error: the surface is that
// close to its triangles.
vec4 faceSphere(Instance inst, uint face) {
  CageFace f = cageFaces[face];
  vec3 corner[4];
  for (uint k = 0u; k < 4u; k++) corner[k] = instanceToWorld(inst, vertexPosition(cageFaceVertices[f.firstVertex + k]));
  vec3 centre = 0.25 * (corner[0] + corner[1] + corner[2] + corner[3]);
  float radius = max(max(distance(centre, corner[0]), distance(centre, corner[1])), max(distance(centre, corner[2]), distance(centre, corner[3])));
  return vec4(centre, radius + patches[face].faceError * inst.maxScale);
}

// Whether the compute rasterizer takes a face of this sphere whose grid is `cells` cells across at the
// least (shaderio_frame.h, VGEO_SOFTWARE_PATCH_MAX_CELL_PIXELS): seen by the draw camera, the sphere lies
// in front of the near plane and, projected, within the guard band (by a wide margin: its corners are
// kept in 32 bits of subpixels).
bool softwareRasterTakesPatch(vec4 sphere, float cells) {
  if (frame.softwarePatches == 0u) return false;
  vec4 clip = frame.viewProjection * vec4(sphere.xyz, 1.0);
  vec3 depthRow = vec3(frame.viewProjection[0][3], frame.viewProjection[1][3], frame.viewProjection[2][3]);
  float nearest = clip.w - sphere.w * length(depthRow);
  if (nearest <= 1.01 * frame.znear) return false;
  float radius = 2.0 * sphere.w * frame.projScale / nearest;  // twice the projected radius, for the sphere's lean
  vec2 centre = screenPosition(clip), viewport = vec2(frame.viewportWidth, frame.viewportHeight);
  if (any(lessThan(centre - radius, vec2(-VGEO_RASTER_GUARD_BAND))) || any(greaterThan(centre + radius, viewport + VGEO_RASTER_GUARD_BAND)))
    return false;
  float cell = radius / cells;
  return frame.softwareRaster == VGEO_RASTER_ALL ? cell * cell <= VGEO_SOFTWARE_RASTER_MAX_AREA / 4.0
                                                 : cell <= VGEO_SOFTWARE_PATCH_MAX_CELL_PIXELS;
}

// The faces of a patch-drawn cluster that may be seen join the patch list, or, when they need no
// tessellation, their triangles join the triangle list. A face for the compute rasterizer reserves its
// grid's points in the patch grid; where they do not fit, the tessellator draws it.
void listPatches(uint entry, Instance inst, Cluster c) {
  uint local = gl_LocalInvocationIndex;
  vec4 sphere = vec4(0.0);
  bool seen = local < clusterCageFaceCount(c.counts);
  if (seen) {
    sphere = faceSphere(inst, c.cageFaceOffset + local);
    seen = sphereInFrustum(sphere);
  }
  bool tessellate = false, software = false;
  uint firstTriangle = 0u, triangles = 0u;
  uvec2 cells = uvec2(1u);
  if (seen) {
    float edge[4], inner[2];
    patchFactors(inst, c.cageFaceOffset + local, edge, inner);
    tessellate = max(max(edge[0], edge[1]), max(edge[2], edge[3])) > 1.0 || max(inner[0], inner[1]) > 1.0;
    software = tessellate && softwareRasterTakesPatch(sphere, min(inner[0], inner[1]));
    cells = uvec2(inner[0], inner[1]);
    firstTriangle = cageFaces[c.cageFaceOffset + local].firstTriangle;
  }
  // With patches in compute every tessellated face has a grid: the rest are drawn from theirs by the
  // hardware (patch_grid.vert) instead of the tessellator.
  bool grid = tessellate && frame.softwarePatches != 0u;
  uint points = grid ? (cells.x + 1u) * (cells.y + 1u) : 0u;
  uint gridPoint = points > 0u ? atomicAdd(sGridPoints, points) : 0u;
  barrier();
  if (local == 0u) sBaseGridPoints = sGridPoints == 0u ? 0u : atomicAdd(counters.patchGridPoints, sGridPoints);
  barrier();
  gridPoint += sBaseGridPoints;
  if (grid && gridPoint + points > frame.patchGridCapacity) {  // the grid is full: its leaf triangles
    tessellate = software = grid = false;
  }
  if (seen && !tessellate) triangles = cageFaces[c.cageFaceOffset + local].vertexCount - 2u;
  uint slot = software ? atomicAdd(sSoftwarePatches, 1u) : tessellate ? atomicAdd(sHardware, 1u) : 0u;
  uint bins[2] = uint[2](triangles > 0u ? binTriangle(inst, c, firstTriangle) : kCulled,
                         triangles > 1u ? binTriangle(inst, c, firstTriangle + 1u) : kCulled);
  listTriangles(entry, firstTriangle, bins);  // its barriers order the reservations above before these
  if (local == 0u) {
    sBaseHardware = sHardware == 0u ? 0u : atomicAdd(counters.hardwarePatches, sHardware);
    sBaseSoftwarePatches = sSoftwarePatches == 0u ? 0u : atomicAdd(counters.softwarePatches, sSoftwarePatches);
    if (sHardware + sSoftwarePatches > 0u) atomicAdd(counters.patchClusters, 1u);
  }
  barrier();
  uint word = entry << VGEO_TRIANGLE_BITS | local;
  if (software) {
    slot = frame.patchCapacity - 1u - (slot + sBaseSoftwarePatches);
    if (slot < frame.patchCapacity) {  // unsigned: past the start wraps above
      patchList[2u * slot] = word;
      patchList[2u * slot + 1u] = gridWord(gridPoint, cells);
    }
  } else if (tessellate) {
    slot += sBaseHardware;
    if (slot < frame.patchCapacity) {
      patchList[2u * slot] = word;
      if (grid) patchList[2u * slot + 1u] = gridWord(gridPoint, cells);
    }
  }
}

void main() {
  uint index = gl_WorkGroupID.y * 65535u + gl_WorkGroupID.x;
  if (index >= counters.patchEntries) return;  // the whole workgroup
  if (gl_LocalInvocationIndex == 0u) {
    sHardware = 0u;
    sSoftwarePatches = 0u;
    sGridPoints = 0u;
    sKeptTriangles = 0u;
    sSoftware = 0u;
  }
  barrier();
  uint entry = patchEntries[index];
  uint instance = drawList[2u * entry], cluster = drawList[2u * entry + 1u] & ~VGEO_DRAW_PATCHES_BIT;
  listPatches(entry, instances[instance], clusters[cluster]);
}
