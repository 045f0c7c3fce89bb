#version 450
// cull_triangles.comp: one workgroup a draw-list entry, one thread a triangle of its cluster. A triangle
// joins the triangle list unless the draw camera cannot see it (Wihlidal, "Optimizing the Graphics
// Pipeline with Compute", GDC 2016):
//   - all three corners beyond one plane of the view volume (left, right, top, bottom, near);
//   - facing away from the eye on a closed, outward-facing instance (the front side hides it);
//   - its screen bounding box holds no pixel centre, so it makes no fragment.
// A leaf cluster flagged for patches (VGEO_DRAW_PATCHES_BIT) lists its cage faces instead, one thread a
// face, in the patch list of the tessellated draw (patch.tesc), unless the face's bounding sphere (its
// corners, grown by its chord error: the surface is that close to its triangles) is outside the frustum.
// A face whose tessellation factors are all 1 (patch_factors.glsl: small on screen, or flat enough)
// would be drawn as its two corner triangles anyway: its leaf triangles join the triangle list instead,
// so the patch list holds only faces that gain from tessellation (about one a few pixels at most).
// A triangle that stays is binned: to the hardware draw (listed from the triangle list's start) or, when
// all its corners are in front of the near plane and it is small on screen (raster_setup.glsl), to the
// software rasterizer (listed from the end, raster_software.comp). finalize_triangles.comp counts an
// overflow when the two meet.
// None of these changes the picture: they keep the rasterizer from setting up triangles that make no
// fragment, which is where the time of a virtual-geometry frame goes once clusters are small on
// screen (docs/gpu-notes.md, 6 and 10). The cut itself (the draw list) is untouched.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "patch_factors.glsl"
#include "raster_setup.glsl"
layout(local_size_x = VGEO_MAX_CLUSTER_TRIANGLES) in;
// A variant without the patch code for frames without patches: lavapipe runs every line of a shader
// whatever its lanes branch to.
layout(constant_id = VGEO_SPEC_PATCHES) const bool kPatches = true;

shared uint sKept, sBase, sKeptTriangles, sBaseTriangles, sSoftware, sBaseSoftware;

const uint kCulled = 0u, kHardware = 1u, kSoftware = 2u;

// Rasterizers snap corners to 1/256 pixel or finer; this slack keeps every triangle the snapped
// corners could make cover a pixel centre.
const float kPixelSlack = 1.0 / 128.0;

bool noPixelCentre(float lo, float hi) {
  return ceil(lo - 0.5 - kPixelSlack) > floor(hi - 0.5 + kPixelSlack);
}

// kCulled, or the rasterizer that draws the triangle.
uint binTriangle(Instance inst, Cluster c, uint triangle) {
  vec3 world[3];
  vec4 clip[3];
  for (uint k = 0u; k < 3u; k++) {
    world[k] = instanceToWorld(inst, vertexPosition(triangleVertex(c, triangle, k)));
    clip[k] = frame.viewProjection * vec4(world[k], 1.0);
  }
  // Outside one plane of the view volume (-w <= x, y <= w; the near plane is z <= w; reversed infinite
  // depth has no far plane). Each is a half-space of clip space, so this holds whatever the signs of w.
  if (all(greaterThan(vec3(clip[0].x, clip[1].x, clip[2].x), vec3(clip[0].w, clip[1].w, clip[2].w))) ||
      all(lessThan(vec3(clip[0].x, clip[1].x, clip[2].x), -vec3(clip[0].w, clip[1].w, clip[2].w))) ||
      all(greaterThan(vec3(clip[0].y, clip[1].y, clip[2].y), vec3(clip[0].w, clip[1].w, clip[2].w))) ||
      all(lessThan(vec3(clip[0].y, clip[1].y, clip[2].y), -vec3(clip[0].w, clip[1].w, clip[2].w))) ||
      all(greaterThan(vec3(clip[0].z, clip[1].z, clip[2].z), vec3(clip[0].w, clip[1].w, clip[2].w))))
    return kCulled;
  if ((inst.flags & VGEO_INSTANCE_CONE_CULL) != 0u) {
    // World-space winding; a mirroring transform (negative determinant) reverses it.
    float det = dot(inst.row0.xyz, cross(inst.row1.xyz, inst.row2.xyz));
    vec3 n = cross(world[1] - world[0], world[2] - world[0]) * sign(det);
    if (dot(n, world[0] - frame.drawEye.xyz) > 0.0) return kCulled;
  }
  // A corner on or behind the near plane cannot be projected: the hardware clips the triangle.
  if (clip[0].z >= clip[0].w || clip[1].z >= clip[1].w || clip[2].z >= clip[2].w) return kHardware;
  vec2 p0 = screenPosition(clip[0]), p1 = screenPosition(clip[1]), p2 = screenPosition(clip[2]);
  vec2 lo = min(p0, min(p1, p2)), hi = max(p0, max(p1, p2));
  if (noPixelCentre(lo.x, hi.x) || noPixelCentre(lo.y, hi.y)) return kCulled;
  return softwareRasterTakes(lo, hi) ? kSoftware : kHardware;
}

bool faceVisible(Instance inst, uint face) {
  CageFace f = cageFaces[face];
  vec3 corner[4];
  for (uint k = 0u; k < 4u; k++) corner[k] = instanceToWorld(inst, vertexPosition(cageFaceVertices[f.firstVertex + k]));
  vec3 centre = 0.25 * (corner[0] + corner[1] + corner[2] + corner[3]);
  float radius = max(max(distance(centre, corner[0]), distance(centre, corner[1])), max(distance(centre, corner[2]), distance(centre, corner[3])));
  return sphereInFrustum(vec4(centre, radius + patches[face].faceError * inst.maxScale));
}

// Lists this lane's triangles first + k with bins[k] != kCulled (k < 2) in the triangle list, hardware
// ones from its start and software ones from its end, with one reservation of each kind a workgroup.
// Called by the whole workgroup (barriers).
void listTriangles(uint entry, uint first, uint bins[2]) {
  uint hardware = uint(bins[0] == kHardware) + uint(bins[1] == kHardware);
  uint software = uint(bins[0] == kSoftware) + uint(bins[1] == kSoftware);
  uint hardwareSlot = hardware > 0u ? atomicAdd(sKeptTriangles, hardware) : 0u;
  uint softwareSlot = software > 0u ? atomicAdd(sSoftware, software) : 0u;
  barrier();
  if (gl_LocalInvocationIndex == 0u) {
    sBaseTriangles = sKeptTriangles == 0u ? 0u : atomicAdd(counters.hardwareTriangles, sKeptTriangles);
    sBaseSoftware = sSoftware == 0u ? 0u : atomicAdd(counters.softwareTriangles, sSoftware);
  }
  barrier();
  hardwareSlot += sBaseTriangles;
  softwareSlot += sBaseSoftware;
  for (uint k = 0u; k < 2u; k++) {
    uint word = entry << VGEO_TRIANGLE_BITS | (first + k);
    if (bins[k] == kHardware) {
      if (hardwareSlot < frame.triangleCapacity) triangleList[hardwareSlot] = word;
      hardwareSlot++;
    } else if (bins[k] == kSoftware) {
      if (softwareSlot < frame.triangleCapacity) triangleList[frame.triangleCapacity - 1u - softwareSlot] = word;
      softwareSlot++;
    }
  }
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
  uint entry = gl_WorkGroupID.y * 65535u + gl_WorkGroupID.x;
  if (entry >= min(counters.drawCount, frame.drawCapacity)) return;  // the whole workgroup
  if (gl_LocalInvocationIndex == 0u) {
    sKept = 0u;
    sKeptTriangles = 0u;
    sSoftware = 0u;
  }
  barrier();
  uint instance = drawList[2u * entry], cluster = drawList[2u * entry + 1u];
  Cluster c = clusters[cluster & ~VGEO_DRAW_PATCHES_BIT];
  if (kPatches && (cluster & VGEO_DRAW_PATCHES_BIT) != 0u) {  // the same for the whole workgroup
    listPatches(entry, instances[instance], c);
    return;
  }
  uint triangle = gl_LocalInvocationIndex;
  uint bins[2] = uint[2](triangle < clusterTriangleCount(c.counts) ? binTriangle(instances[instance], c, triangle) : kCulled, kCulled);
  listTriangles(entry, triangle, bins);
}
