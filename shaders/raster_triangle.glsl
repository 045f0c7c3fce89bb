// raster_triangle.glsl: one triangle into the visibility buffer by one invocation, with the hardware's
// rules, so that a triangle covers the same pixels whichever rasterizer draws it (raster_software.comp
// for listed triangles, raster_patches.comp for the micro-triangles of patches):
//   - corners snapped to 1/VGEO_SUBPIXEL_SCALE pixel, samples at pixel centres;
//   - a sample on an edge belongs to the triangle if the edge is a top edge (horizontal, the triangle
//     below it) or a left edge (the triangle to its right): two triangles sharing an edge never both
//     cover a sample on it, and never leave it uncovered;
//   - depth interpolated linearly in screen space from the corners' z / w (reversed infinite depth:
//     larger is nearer), kept nearest-first by a 64-bit atomicMax of (depth, id) (visibility.glsl).
// Both faces are drawn (open meshes are seen from both sides). Edge functions are exact in 64-bit
// integers on the snapped corners. In --mode overdraw every covered sample counts instead. Needs
// common.glsl and visibility.glsl.

// Corners v (snapped, in 1/VGEO_SUBPIXEL_SCALE pixels, within the guard band) with depths z.
void rasterTriangle(i64vec2 v[3], float z[3], uint64_t id) {
  int64_t area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x);
  if (area == 0l) return;  // no sample is inside a degenerate triangle
  if (area < 0l) {  // counter-clockwise on screen: the same triangle with the inside on the left
    i64vec2 tv = v[1];
    v[1] = v[2];
    v[2] = tv;
    float tz = z[1];
    z[1] = z[2];
    z[2] = tz;
    area = -area;
  }
  // Edge i runs from corner i + 1 to corner i + 2 (opposite corner i): e_i(p) = cross(b - a, p - a), >= 0
  // inside, its steps per pixel dx, dy; a sample on the edge is inside when the edge is top or left.
  int64_t dx[3], dy[3], bias[3];
  for (uint i = 0u; i < 3u; i++) {
    i64vec2 a = v[(i + 1u) % 3u], b = v[(i + 2u) % 3u];
    dx[i] = -(b.y - a.y);
    dy[i] = b.x - a.x;
    bool topLeft = dx[i] > 0l || (dx[i] == 0l && dy[i] > 0l);
    bias[i] = topLeft ? 0l : -1l;
  }
  const int64_t scale = int64_t(VGEO_SUBPIXEL_SCALE), centre = scale / 2l;
  i64vec2 lo = min(v[0], min(v[1], v[2])), hi = max(v[0], max(v[1], v[2]));
  // Pixels whose centre (x * scale + centre) lies in the box, within the viewport.
  int x0 = int(max((lo.x - centre + scale - 1l) / scale, 0l)), y0 = int(max((lo.y - centre + scale - 1l) / scale, 0l));
  int x1 = int(min((hi.x - centre) / scale, int64_t(frame.viewportWidth) - 1l));
  int y1 = int(min((hi.y - centre) / scale, int64_t(frame.viewportHeight) - 1l));
  if (lo.x - centre < 0l) x0 = 0;  // the division above rounds toward zero
  if (lo.y - centre < 0l) y0 = 0;
  const uint width = uint(frame.viewportWidth);
  const float invArea = 1.0 / float(area);
  // The pixel loop is written out per edge: lavapipe counts every loop iteration (docs/gpu-notes.md, 1).
  const int64_t step0 = dx[0] * scale, step1 = dx[1] * scale, step2 = dx[2] * scale;
  const i64vec2 a0 = v[1], a1 = v[2], a2 = v[0];
  for (int y = y0; y <= y1; y++) {
    const int64_t px = int64_t(x0) * scale + centre, py = int64_t(y) * scale + centre;
    int64_t e0 = dx[0] * (px - a0.x) + dy[0] * (py - a0.y) + bias[0];
    int64_t e1 = dx[1] * (px - a1.x) + dy[1] * (py - a1.y) + bias[1];
    int64_t e2 = dx[2] * (px - a2.x) + dy[2] * (py - a2.y) + bias[2];
    for (int x = x0; x <= x1; x++) {
      if (e0 >= 0l && e1 >= 0l && e2 >= 0l) {
        uint pixel = uint(y) * width + uint(x);
        if (frame.mode == VGEO_MODE_OVERDRAW) {
          atomicAdd(overdraw[pixel], 1u);
        } else {
          float depth = (float(e0 - bias[0]) * z[0] + float(e1 - bias[1]) * z[1] + float(e2 - bias[2]) * z[2]) * invArea;
          atomicMax(visibility[pixel], visibilityWord(depth, id));
        }
      }
      e0 += step0;
      e1 += step1;
      e2 += step2;
    }
  }
}
