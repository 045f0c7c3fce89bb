#version 450
// cull_patches.comp: one workgroup a patch-drawn leaf cluster (the patch-entry list of
// cull_triangles.comp), one thread a cage face. A face joins the patch list of the tessellated draw
// (patch.tesc) unless its bounding sphere (its corners, grown by its chord error: the surface is that
// close to its triangles) is outside the frustum. A face whose tessellation factors are all 1
// (patch_factors.glsl: small on screen, or flat enough) would be drawn as its two corner triangles
// anyway: its leaf triangles join the triangle list instead (binned as cull_triangles.comp bins), so the
// patch list holds only faces that gain from tessellation (about one a few pixels at most).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "patch_factors.glsl"
#include "raster_setup.glsl"
layout(local_size_x = VGEO_MAX_CLUSTER_TRIANGLES) in;
#include "cull_triangles.glsl"

shared uint sKept, sBase;

bool faceVisible(Instance inst, uint face) {
  CageFace f = cageFaces[face];
  vec3 corner[4];
  for (uint k = 0u; k < 4u; k++) corner[k] = instanceToWorld(inst, vertexPosition(cageFaceVertices[f.firstVertex + k]));
  vec3 centre = 0.25 * (corner[0] + corner[1] + corner[2] + corner[3]);
  float radius = max(max(distance(centre, corner[0]), distance(centre, corner[1])), max(distance(centre, corner[2]), distance(centre, corner[3])));
  return sphereInFrustum(vec4(centre, radius + patches[face].faceError * inst.maxScale));
}

// The faces of a patch-drawn cluster that may be seen join the patch list, or, when they need no
// tessellation, their triangles join the triangle list.
void listPatches(uint entry, Instance inst, Cluster c) {
  uint local = gl_LocalInvocationIndex;
  bool seen = local < clusterCageFaceCount(c.counts) && faceVisible(inst, c.cageFaceOffset + local);
  bool tessellate = false;
  uint firstTriangle = 0u, triangles = 0u;
  if (seen) {
    float edge[4], inner[2];
    patchFactors(inst, c.cageFaceOffset + local, edge, inner);
    tessellate = max(max(edge[0], edge[1]), max(edge[2], edge[3])) > 1.0 || max(inner[0], inner[1]) > 1.0;
    CageFace f = cageFaces[c.cageFaceOffset + local];
    firstTriangle = f.firstTriangle;
    triangles = tessellate ? 0u : f.vertexCount - 2u;
  }
  uint slot = tessellate ? atomicAdd(sKept, 1u) : 0u;
  uint bins[2] = uint[2](triangles > 0u ? binTriangle(inst, c, firstTriangle) : kCulled,
                         triangles > 1u ? binTriangle(inst, c, firstTriangle + 1u) : kCulled);
  listTriangles(entry, firstTriangle, bins);
  if (gl_LocalInvocationIndex == 0u) {
    sBase = sKept == 0u ? 0u : atomicAdd(counters.patchesDrawn, sKept);
    uint end = sBase + sKept;
    if (end > frame.patchCapacity) atomicAdd(counters.patchOverflow, min(sKept, end - frame.patchCapacity));
    if (sKept > 0u) atomicAdd(counters.patchClusters, 1u);
  }
  barrier();
  slot += sBase;
  if (tessellate && slot < frame.patchCapacity) patchList[slot] = entry << VGEO_TRIANGLE_BITS | local;
}

void main() {
  uint index = gl_WorkGroupID.y * 65535u + gl_WorkGroupID.x;
  if (index >= counters.patchEntries) return;  // the whole workgroup
  if (gl_LocalInvocationIndex == 0u) {
    sKept = 0u;
    sKeptTriangles = 0u;
    sSoftware = 0u;
  }
  barrier();
  uint entry = patchEntries[index];
  uint instance = drawList[2u * entry], cluster = drawList[2u * entry + 1u] & ~VGEO_DRAW_PATCHES_BIT;
  listPatches(entry, instances[instance], clusters[cluster]);
}
