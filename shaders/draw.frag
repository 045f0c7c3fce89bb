#version 450
// draw.frag: the debug views of `--mode` (lit, normal, cluster, group, lod, triangle, instance, error,
// wire, overdraw, frozen-diff, patch). Ids get stable colours from a hash, so the same cluster keeps its colour
// from frame to frame and between runs.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec3 inBarycentric;
layout(location = 2) flat in uvec4 inIds;
layout(location = 3) flat in vec2 inInfo;
layout(location = 4) flat in uint inTriangle;
layout(location = 0) out vec4 outColor;

uint hash(uint x) {
  x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
  return x;
}
vec3 idColor(uint id) {
  uint h = hash(id + 0x9e3779b9u);
  float hue = float(h & 0xffffu) / 65535.0;
  vec3 rgb = clamp(abs(fract(hue + vec3(0.0, 2.0 / 3.0, 1.0 / 3.0)) * 6.0 - 3.0) - 1.0, 0.0, 1.0);
  float value = 0.65 + 0.35 * float((h >> 16) & 0xffu) / 255.0;
  return mix(vec3(1.0), rgb, 0.75) * value;
}
vec3 heat(float t) {  // 0 blue, 0.5 green, 1 red
  t = clamp(t, 0.0, 1.0);
  return clamp(vec3(2.0 * t - 0.5, 1.0 - abs(2.0 * t - 1.0) * 1.2 + 0.2, 1.5 - 2.0 * t), 0.0, 1.0);
}
float lighting(vec3 n) {
  vec3 l = normalize(vec3(0.4, 0.8, 0.45));
  return 0.18 + 0.82 * max(dot(n, l), 0.0);
}

void main() {
  vec3 n = normalize(inNormal);
  if (!gl_FrontFacing) n = -n;
  float light = lighting(n);
  uint mode = frame.mode;
  vec3 color;
  if (mode == VGEO_MODE_NORMAL) color = n * 0.5 + 0.5;
  else if (mode == VGEO_MODE_CLUSTER) color = idColor(inIds.x) * light;
  else if (mode == VGEO_MODE_GROUP) color = idColor(inIds.y) * light;
  else if (mode == VGEO_MODE_LOD) color = heat(float(inIds.w) / 12.0) * light;
  else if (mode == VGEO_MODE_TRIANGLE) color = idColor(inIds.x * 131u + inTriangle) * light;
  else if (mode == VGEO_MODE_INSTANCE) color = idColor(inIds.z) * light;
  else if (mode == VGEO_MODE_ERROR) color = heat(inInfo.x) * light;  // projected error / tau: red at tau
  else if (mode == VGEO_MODE_OVERDRAW) color = vec3(0.09, 0.05, 0.02);
  else if (mode == VGEO_MODE_PATCH)  // patches by their largest tessellation factor (blue 1, green 8, red 64); triangles grey
    color = (inInfo.x < 0.0 ? vec3(0.55) : heat(inInfo.x)) * light;
  else if (mode == VGEO_MODE_FROZEN_DIFF)
    color = (inInfo.y == 0.0 ? vec3(0.3, 0.85, 0.3) : inInfo.y == 1.0 ? vec3(0.95, 0.3, 0.25) : vec3(0.3, 0.45, 0.95)) * light;
  else color = vec3(0.82, 0.8, 0.76) * light;
  if (mode == VGEO_MODE_WIRE) {
    vec3 d = fwidth(inBarycentric);
    vec3 a = smoothstep(vec3(0.0), d * 1.2, inBarycentric);
    float edge = 1.0 - min(min(a.x, a.y), a.z);
    color = mix(color, vec3(0.05, 0.1, 0.2), edge * 0.85);
  }
  outColor = vec4(color, 1.0);
}
