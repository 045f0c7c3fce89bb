// cull_triangles.glsl: what triangle culling (cull_triangles.comp) and patch culling (cull_patches.comp)
// share: a triangle's bin (culled, hardware or software rasterizer) and the workgroup's listing of its
// lanes' triangles in the triangle list. Needs common.glsl and raster_setup.glsl; workgroups of
// VGEO_MAX_CLUSTER_TRIANGLES lanes.

shared uint sKeptTriangles, sBaseTriangles, sSoftware, sBaseSoftware;

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
