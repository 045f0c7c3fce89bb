#version 450
// resolve.frag: the pixels of the software rasterizer (raster_software.comp), shaded from the
// visibility buffer in the view of --mode, first thing in the render pass; it writes their depth, so the
// hardware draws after it keep the nearest surface either way. From a pixel's triangle word: the
// draw-list entry (instance, cluster) and the triangle, whose corners are projected again to find the
// pixel centre's barycentric coordinates (made perspective-correct with the corners' w) for the normal,
// and the distance to the edges in pixels for the wire view. Empty pixels are discarded. In
// --mode overdraw the pixel adds its count of software-rasterized samples instead.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "raster_setup.glsl"
#define VGEO_VISIBILITY_ACCESS readonly
#include "visibility.glsl"
#include "shade.glsl"

layout(location = 0) out vec4 outColor;

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

void main() {
  uint pixel = uint(gl_FragCoord.y) * uint(frame.viewportWidth) + uint(gl_FragCoord.x);
  gl_FragDepth = 0.0;
  if (frame.mode == VGEO_MODE_OVERDRAW) {
    uint samples = overdraw[pixel];
    if (samples == 0u) discard;
    outColor = vec4(kOverdrawColor * float(samples), 1.0);
    return;
  }
  uint64_t word = visibility[pixel];
  if (word == 0ul) discard;
  uint triangleWord = uint(word & 0xfffffffful);
  uint entry = triangleWord >> VGEO_TRIANGLE_BITS, triangle = triangleWord & ((1u << VGEO_TRIANGLE_BITS) - 1u);
  uint instance = drawList[2u * entry], cluster = drawList[2u * entry + 1u] & ~VGEO_DRAW_PATCHES_BIT;
  Instance inst = instances[instance];
  Cluster c = clusters[cluster];
  vec2 s[3];
  float w[3];
  vec3 n[3];
  for (uint i = 0u; i < 3u; i++) {
    uint vertex = triangleVertex(c, triangle, i);
    vec4 clip = clipPosition(inst, vertexPosition(vertex));
    s[i] = screenPosition(clip);
    w[i] = clip.w;
    n[i] = normalToWorld(inst, decodeNormal(normals[vertex]));
  }
  // Barycentric coordinate i: the edge from corner i + 1 to i + 2, over the whole.
  vec2 p = gl_FragCoord.xy;
  float area = cross2(s[1] - s[0], s[2] - s[0]);
  vec3 edgeX = vec3(s[2].x - s[1].x, s[0].x - s[2].x, s[1].x - s[0].x);
  vec3 edgeY = vec3(s[2].y - s[1].y, s[0].y - s[2].y, s[1].y - s[0].y);
  vec3 l = vec3(cross2(s[2] - s[1], p - s[1]), cross2(s[0] - s[2], p - s[2]), cross2(s[1] - s[0], p - s[0])) / area;
  vec3 b = l / vec3(w[0], w[1], w[2]);
  b /= b.x + b.y + b.z;
  vec3 normal = normalize(b.x * n[0] + b.y * n[1] + b.z * n[2]);
  // Vulkan's front face (counter-clockwise, framebuffer y down) has a negative cross product here.
  if (area > 0.0) normal = -normal;
  float edge = 0.0;
  if (frame.mode == VGEO_MODE_WIRE) {
    vec3 d = (abs(edgeX) + abs(edgeY)) / abs(area);  // |dl/dx| + |dl/dy|, as fwidth would give
    vec3 a = smoothstep(vec3(0.0), d * 1.2, l);
    edge = 1.0 - min(min(a.x, a.y), a.z);
  }
  uvec4 ids = uvec4(cluster, c.group, instance, clusterLevel(c.counts));
  outColor = vec4(shadeSurface(normal, ids, triangle, clusterViewInfo(inst, c), edge), 1.0);
  gl_FragDepth = uintBitsToFloat(uint(word >> 32));
}
