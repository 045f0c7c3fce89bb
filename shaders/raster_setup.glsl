// raster_setup.glsl: a listed triangle's corners on screen, as the rasterizers see them: triangle
// culling bins triangles with it (cull_triangles.comp), the software rasterizer covers pixels with it
// (raster_software.comp) and the resolve finds a pixel's surface point with it (resolve.comp). Needs
// common.glsl.

// Corner k's vertex of triangle `triangle` of cluster c.
uint triangleVertex(Cluster c, uint triangle, uint k) {
  uint packed = clusterTriangles[c.triangleOffset + triangle];
  return clusterVertices[c.vertexOffset + ((packed >> (8u * k)) & 0xffu)];
}

// Framebuffer position (pixels, y down) of a clip-space point in front of the camera.
vec2 screenPosition(vec4 clip) {
  return (clip.xy / clip.w * 0.5 + 0.5) * vec2(frame.viewportWidth, frame.viewportHeight);
}

// Whether the software rasterizer takes a triangle whose corners are all in front of the near plane,
// with this screen box (shaderio_frame.h, VGEO_RASTER_*).
bool softwareRasterTakes(vec2 lo, vec2 hi) {
  if (frame.softwareRaster == VGEO_RASTER_SMALL)
    return max(hi.x - lo.x, hi.y - lo.y) <= VGEO_SOFTWARE_RASTER_MAX_PIXELS;
  if (frame.softwareRaster != VGEO_RASTER_ALL) return false;
  vec2 viewport = vec2(frame.viewportWidth, frame.viewportHeight);
  if (any(lessThan(lo, vec2(-VGEO_RASTER_GUARD_BAND))) || any(greaterThan(hi, viewport + VGEO_RASTER_GUARD_BAND)))
    return false;
  vec2 size = min(hi, viewport) - max(lo, vec2(0.0)) + 1.0;
  return max(size.x, 0.0) * max(size.y, 0.0) <= VGEO_SOFTWARE_RASTER_MAX_AREA;
}
