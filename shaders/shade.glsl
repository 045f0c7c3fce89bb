// shade.glsl: the debug views of `--mode` (lit, normal, cluster, group, lod, triangle, instance, error,
// wire, overdraw, frozen-diff, patch), one function for every path that makes a pixel: the hardware draws
// (draw.frag) and the visibility-buffer resolve (resolve.comp). Ids get stable colours from a hash, so
// the same cluster keeps its colour from frame to frame and between runs. Needs common.glsl.

uint hashId(uint x) {
  x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
  return x;
}
vec3 idColor(uint id) {
  uint h = hashId(id + 0x9e3779b9u);
  float hue = float(h & 0xffffu) / 65535.0;
  vec3 rgb = clamp(abs(fract(hue + vec3(0.0, 2.0 / 3.0, 1.0 / 3.0)) * 6.0 - 3.0) - 1.0, 0.0, 1.0);
  float value = 0.65 + 0.35 * float((h >> 16) & 0xffu) / 255.0;
  return mix(vec3(1.0), rgb, 0.75) * value;
}
vec3 heat(float t) {  // 0 blue, 0.5 green, 1 red
  t = clamp(t, 0.0, 1.0);
  return clamp(vec3(2.0 * t - 0.5, 1.0 - abs(2.0 * t - 1.0) * 1.2 + 0.2, 1.5 - 2.0 * t), 0.0, 1.0);
}
// The view: frame.mode, or where the includer defines VGEO_VIEW_MODE (a specialization constant) that,
// so that its compiler drops the other views' code.
#ifndef VGEO_VIEW_MODE
#define VGEO_VIEW_MODE frame.mode
#endif

// What one fragment adds in the overdraw view (additive blending).
const vec3 kOverdrawColor = vec3(0.09, 0.05, 0.02);

// A colour as the colour target holds it: R, G, B, or B, G, R for the viewer's BGRA window (a copy
// there, not a converting blit). Swapping twice gives back the colour.
vec4 targetColor(vec3 c) { return vec4(frame.bgraTarget != 0u ? c.bgr : c, 1.0); }
float lighting(vec3 n) {
  vec3 l = frame.light.w != 0.0 ? frame.light.xyz : normalize(vec3(0.4, 0.8, 0.45));  // the viewer's, or fixed
  return 0.18 + 0.82 * max(dot(n, l), 0.0);
}

// What the error and frozen-diff views show of a cluster drawn as triangles: its projected self error
// / tau (-1 in the patch view: triangles are grey there), and whether the live (draw) camera would pick
// it too: 0 yes, 1 it wants finer, 2 coarser.
vec2 clusterViewInfo(Instance inst, Cluster c) {
  float self = projectedErrorWorld(inst, c.selfSphere, c.selfError);
  float liveSelf = projectedError(worldSphere(inst, c.selfSphere), c.selfError * inst.maxScale, frame.drawEye.xyz, frame.projScale, frame.znear);
  float liveParent = projectedError(worldSphere(inst, c.parentSphere), c.parentError * inst.maxScale, frame.drawEye.xyz, frame.projScale, frame.znear);
  float state = liveSelf > frame.tau ? 1.0 : (liveParent <= frame.tau ? 2.0 : 0.0);
  return vec2(VGEO_VIEW_MODE == VGEO_MODE_PATCH ? -1.0 : self / frame.tau, state);
}

// What the patch, error and frozen-diff views show of a patch of a cluster whose largest tessellation
// factor is `largest`: log2(largest) / 6 (1 -> 0, 64 -> 1) in the patch view, else the cluster's
// projected self error / tau; the frozen-diff state 0.
vec2 patchViewInfo(Instance inst, Cluster c, float largest) {
  return vec2(VGEO_VIEW_MODE == VGEO_MODE_PATCH ? log2(largest) / 6.0 : projectedErrorWorld(inst, c.selfSphere, c.selfError) / frame.tau, 0.0);
}

// The colour of a surface point: n its world normal facing the eye, ids (cluster, group, instance,
// level), its triangle in the cluster, info as clusterViewInfo (or a patch's), edge in [0, 1] how close
// it lies to its triangle's edge (the wire view).
vec3 shadeSurface(vec3 n, uvec4 ids, uint triangle, vec2 info, float edge) {
  float light = lighting(n);
  uint mode = VGEO_VIEW_MODE;
  vec3 color;
  if (mode == VGEO_MODE_NORMAL) color = n * 0.5 + 0.5;
  else if (mode == VGEO_MODE_CLUSTER) color = idColor(ids.x) * light;
  else if (mode == VGEO_MODE_GROUP) color = idColor(ids.y) * light;
  else if (mode == VGEO_MODE_LOD) color = heat(float(ids.w) / float(max(frame.lodLevels, 2u) - 1u)) * light;
  else if (mode == VGEO_MODE_TRIANGLE) color = idColor(ids.x * 131u + triangle) * light;
  else if (mode == VGEO_MODE_INSTANCE) color = idColor(ids.z) * light;
  else if (mode == VGEO_MODE_ERROR) color = heat(info.x) * light;  // projected error / tau: red at tau
  else if (mode == VGEO_MODE_OVERDRAW) color = kOverdrawColor;
  else if (mode == VGEO_MODE_PATCH)  // patches by their largest tessellation factor (blue 1, green 8, red 64); triangles grey
    color = (info.x < 0.0 ? vec3(0.55) : heat(info.x)) * light;
  else if (mode == VGEO_MODE_FROZEN_DIFF)
    color = (info.y == 0.0 ? vec3(0.3, 0.85, 0.3) : info.y == 1.0 ? vec3(0.95, 0.3, 0.25) : vec3(0.3, 0.45, 0.95)) * light;
  else color = vec3(0.82, 0.8, 0.76) * light;
  if (mode == VGEO_MODE_WIRE) color = mix(color, vec3(0.05, 0.1, 0.2), edge * 0.85);
  return color;
}
