#version 450
// resolve.comp: the pixels of the compute rasterizers (raster_software.comp, raster_patches.comp), shaded
// from the visibility buffer in the view of --mode after the render pass, one thread a pixel: where its
// depth is at least the hardware draws' (the nearest surface either way; a tie goes to the compute
// pixel), its colour is written over theirs. A pixel's id names a listed triangle (draw-list entry:
// instance and cluster, and the triangle) or a patch's micro-triangle (patch-list slot: the entry, and
// the grid whose points raster_patches.comp left in the patch grid). The triangle's corners are projected
// again to find the pixel centre's barycentric coordinates (made perspective-correct with the corners'
// w) for the normal, and the distance to the edges in pixels for the wire view. A pixel nothing covers
// gets the background (the render pass leaves the colour uncleared then). In --mode overdraw the pixel
// adds its count of compute-rasterized samples instead. The view is a specialization constant (one
// pipeline a view: see docs/gpu-notes.md, 17), and so are whether the frame has patches in the visibility
// buffer and whether the render pass left every pixel to it (its triangles in the visibility buffer too,
// draw_visibility.frag).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "raster_setup.glsl"
#include "patch_surface.glsl"
#define VGEO_VISIBILITY_ACCESS readonly
#include "visibility.glsl"
layout(constant_id = VGEO_SPEC_VIEW_MODE) const uint kViewMode = VGEO_MODE_LIT;
layout(constant_id = VGEO_SPEC_RESOLVE_PATCHES) const bool kPatches = false;
// Whether the render pass had no attachments (its triangles are in the visibility buffer too): then
// every pixel is this pass's, and the depth image is not read.
layout(constant_id = VGEO_SPEC_RESOLVE_EVERY_PIXEL) const bool kEveryPixel = false;
#define VGEO_VIEW_MODE kViewMode
#include "shade.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = VGEO_BINDING_COLOR_IMAGE, rgba8) uniform image2D colorImage;
layout(set = 0, binding = VGEO_BINDING_DEPTH_IMAGE) uniform sampler2D depthImage;
layout(set = 0, binding = VGEO_BINDING_DEPTH_PYRAMID, std430) readonly buffer DepthPyramidBuffer { float depthPyramid[]; };

// The pyramid view: the texel of level frame.pyramidViewLevel over this pixel, grey by distance (nearer
// brighter), black where the texel holds no depth (something under it was not drawn: it hides nothing).
// znear is 1e-4 of the distance to the scene's far side (camera.cpp), so depth x 1e4 is that distance
// over the texel's: the grey spans 5 octaves of it.
vec3 pyramidColor(ivec2 xy) {
  const uint level = frame.pyramidViewLevel;
  const uint width = (uint(frame.viewportWidth) + (1u << level) - 1u) >> level;
  const float depth = depthPyramid[frame.pyramidOffsets[level >> 2u][level & 3u] + (uint(xy.y) >> level) * width + (uint(xy.x) >> level)];
  return depth > 0.0 ? vec3(0.15 + 0.85 * clamp(log2(depth * 1e4) / 5.0, 0.0, 1.0)) : vec3(0.0);
}

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

void main() {
  ivec2 xy = ivec2(gl_GlobalInvocationID.xy);
  if (xy.x >= int(frame.viewportWidth) || xy.y >= int(frame.viewportHeight)) return;
  uint pixel = uint(xy.y) * uint(frame.viewportWidth) + uint(xy.x);
  if (VGEO_VIEW_MODE == VGEO_MODE_PYRAMID) {
    imageStore(colorImage, xy, targetColor(pyramidColor(xy)));
    return;
  }
  if (VGEO_VIEW_MODE == VGEO_MODE_OVERDRAW) {
    uint samples = overdraw[pixel];
    if (kEveryPixel) {
      vec3 background = vec3(VGEO_BACKGROUND_R, VGEO_BACKGROUND_G, VGEO_BACKGROUND_B);
      imageStore(colorImage, xy, targetColor(background + kOverdrawColor * float(samples)));
    } else if (samples != 0u) {
      imageStore(colorImage, xy, targetColor(targetColor(imageLoad(colorImage, xy).rgb).rgb + kOverdrawColor * float(samples)));
    }
    return;
  }
  uint64_t word = visibility[pixel];
  float drawnDepth = kEveryPixel ? 0.0 : texelFetch(depthImage, xy, 0).r;  // 0: the render pass drew nothing here
  if (word == 0ul) {
    if (drawnDepth == 0.0) imageStore(colorImage, xy, targetColor(vec3(VGEO_BACKGROUND_R, VGEO_BACKGROUND_G, VGEO_BACKGROUND_B)));
    return;
  }
  if (visibilityDepth(word) < drawnDepth) return;
  uint64_t id = visibilityId(word);
  vec2 s[3];
  float w[3];
  vec3 n[3];  // object space: one transform of the interpolated normal, not three
  uint triangle, instance, cluster;
  float largestFactor = 1.0;
  bool isPatch = kPatches && (id & VGEO_VISIBILITY_PATCH_BIT) != 0ul;
  if (isPatch) {
    uint slot = uint(id >> VGEO_PATCH_TRIANGLE_BITS) & (VGEO_MAX_PATCH_ENTRIES - 1u);
    uint gridTriangle = uint(id) & ((1u << VGEO_PATCH_TRIANGLE_BITS) - 1u);
    uint entry = patchList[2u * slot] >> VGEO_TRIANGLE_BITS, grid = patchList[2u * slot + 1u];
    instance = drawList[2u * entry];
    cluster = drawList[2u * entry + 1u] & ~VGEO_DRAW_PATCHES_BIT;
    Instance inst = instances[instance];
    uvec2 cells = gridCells(grid);
    largestFactor = float(max(cells.x, cells.y));  // an inner factor is at least its edges'
    for (uint i = 0u; i < 3u; i++) {
      uvec2 at = gridTriangleCorner(cells, gridTriangle, i);
      vec4 point = patchGrid[gridOffset(grid) + at.y * (cells.x + 1u) + at.x];
      vec4 clip = clipPosition(inst, point.xyz);
      s[i] = screenPosition(clip);
      w[i] = clip.w;
      n[i] = decodeNormal(floatBitsToUint(point.w));
    }
    triangle = 0u;  // as the tessellated draw (patch.tese): a patch is one triangle of its cluster there
  } else {
    uint triangleWord = uint(id);
    uint entry = triangleWord >> VGEO_TRIANGLE_BITS;
    triangle = triangleWord & ((1u << VGEO_TRIANGLE_BITS) - 1u);
    instance = drawList[2u * entry];
    cluster = drawList[2u * entry + 1u] & ~VGEO_DRAW_PATCHES_BIT;
    Instance inst = instances[instance];
    Cluster c = clusters[cluster];
    for (uint i = 0u; i < 3u; i++) {
      uint vertex = triangleVertex(c, triangle, i);
      vec4 clip = clipPosition(inst, vertexPosition(vertex));
      s[i] = screenPosition(clip);
      w[i] = clip.w;
      n[i] = decodeNormal(normals[vertex]);
    }
  }
  Instance inst = instances[instance];
  Cluster c = clusters[cluster];
  // Barycentric coordinate i: the edge from corner i + 1 to i + 2, over the whole.
  vec2 p = vec2(xy) + 0.5;
  float area = cross2(s[1] - s[0], s[2] - s[0]);
  vec3 edgeX = vec3(s[2].x - s[1].x, s[0].x - s[2].x, s[1].x - s[0].x);
  vec3 edgeY = vec3(s[2].y - s[1].y, s[0].y - s[2].y, s[1].y - s[0].y);
  vec3 l = vec3(cross2(s[2] - s[1], p - s[1]), cross2(s[0] - s[2], p - s[2]), cross2(s[1] - s[0], p - s[0])) / area;
  vec3 b = l / vec3(w[0], w[1], w[2]);
  b /= b.x + b.y + b.z;
  vec3 normal = normalToWorld(inst, b.x * n[0] + b.y * n[1] + b.z * n[2]);
  // Vulkan's front face (counter-clockwise, framebuffer y down) has a negative cross product here.
  if (area > 0.0) normal = -normal;
  float edge = 0.0;
  if (VGEO_VIEW_MODE == VGEO_MODE_WIRE && !isPatch) {  // as patch.tese: no wire on patches
    vec3 d = (abs(edgeX) + abs(edgeY)) / abs(area);  // |dl/dx| + |dl/dy|, as fwidth would give
    vec3 a = smoothstep(vec3(0.0), d * 1.2, l);
    edge = 1.0 - min(min(a.x, a.y), a.z);
  }
  uvec4 ids = uvec4(cluster, c.group, instance, clusterLevel(c.counts));
  // The projected errors only where a view shows them.
  bool errorView = VGEO_VIEW_MODE == VGEO_MODE_ERROR || VGEO_VIEW_MODE == VGEO_MODE_FROZEN_DIFF;
  vec2 info = errorView ? clusterViewInfo(inst, c) : vec2(-1.0, 0.0);
  if (isPatch && (errorView || VGEO_VIEW_MODE == VGEO_MODE_PATCH)) info = patchViewInfo(inst, c, largestFactor);
  imageStore(colorImage, xy, targetColor(shadeSurface(normal, ids, triangle, info, edge)));
}
