// occlusion.glsl: the occlusion test of the two passes (docs/design.md, "Occlusion culling"): a bounding
// sphere is hidden when the nearest depth it can have is farther than the farthest depth drawn over every
// pixel its screen bounds touch, read from the depth pyramid (build_depth_pyramid.comp) at the level where
// those bounds span at most 2x2 texels (the hierarchical z-buffer of Greene, Kass and Miller 1993, in two
// passes as in Karis, "Nanite", SIGGRAPH 2021). The early pass tests against the last frame's pyramid and
// only defers what it hides; the late pass tests that against the pyramid of what the early pass drew,
// a subset of what the frame draws: every pixel's early depth is as far as or farther than its final one,
// so what it hides is hidden in the final picture, and the picture is the same as without the tests.

layout(set = 0, binding = VGEO_BINDING_DEPTH_PYRAMID, std430) readonly buffer DepthPyramidBuffer { float depthPyramid[]; };
layout(set = 0, binding = VGEO_BINDING_DEFERRED_INSTANCES, std430) buffer DeferredInstanceBuffer { uint deferredInstances[]; };
// Deferred item i: (instance, code) in deferredItems[2i], [2i + 1], codes as the queue's; a cluster is
// a sweep run of one (VGEO_ITEM_RUN_BIT).
layout(set = 0, binding = VGEO_BINDING_DEFERRED_ITEMS, std430) buffer DeferredItemBuffer { uint deferredItems[]; };

// Depth and radius slack: float rounding in the transforms and the rasterizers' depth never makes a
// sphere look farther than what it holds.
const float kOcclusionSlack = 1.0001;

// The instances a pass culls: every one, or in the late pass those the early pass deferred (their count,
// counters.deferredInstances, is final before the late pass starts). Index i of the pass to an instance
// (VGEO_INVALID past the end).
uint passInstanceCount() { return passConstants.pass == VGEO_PASS_LATE ? counters.deferredInstances : frame.instanceCount; }
uint passInstance(uint i) {
  if (passConstants.pass != VGEO_PASS_LATE) return i;
  return i < counters.deferredInstances ? deferredInstances[i] : VGEO_INVALID;
}

layout(constant_id = VGEO_SPEC_OCCLUSION) const bool kOcclusionTests = true;  // false: one-pass pipelines
bool occlusionTests() {
  return kOcclusionTests &&
         (passConstants.pass == VGEO_PASS_LATE || (passConstants.pass == VGEO_PASS_EARLY && frame.earlyOcclusion != 0u));
}

float pyramidTexel(uint level, uint x, uint y) {
  uint width = (uint(frame.viewportWidth) + (1u << level) - 1u) >> level;
  return depthPyramid[frame.pyramidOffsets[level >> 2u][level & 3u] + y * width + x];
}

// The farthest of texels x0, x1, x2 of row y of `level`.
float pyramidRow(uint level, uint x0, uint x1, uint x2, uint y) {
  return min(min(pyramidTexel(level, x0, y), pyramidTexel(level, x1, y)), pyramidTexel(level, x2, y));
}

// A sphere's bounds along one screen axis, as (min, max) of clip / w: in the plane of that axis and the
// view direction, the two tangents from the eye to the circle at the centre's angle plus and minus
// asin(r / distance), their slopes by the tangent of a sum, times depth and sqrt(distance^2 - r^2) (Mara
// and McGuire 2013). Both denominators are positive while depth > r. No loop over the axes: lavapipe
// counts every loop iteration against its limit (docs/gpu-notes.md, 1).
vec2 screenSpan(float centre, float depth, float r, float scale) {
  float q = sqrt(max(centre * centre + depth * depth - r * r, 0.0));
  float t0 = (centre * q - r * depth) / (depth * q + centre * r), t1 = (centre * q + r * depth) / (depth * q - centre * r);
  return vec2(min(scale * t0, scale * t1), max(scale * t0, scale * t1));
}

// Whether the world-space sphere s is hidden by the pyramid's depth, seen by the camera it was drawn from.
bool sphereOccluded(vec4 s) {
  const uint late = passConstants.pass == VGEO_PASS_LATE ? 1u : 0u;
  const vec2 scale = late != 0u ? frame.pyramidProjections.zw : frame.pyramidProjections.xy;
  const float znear = frame.pyramidZnear[late];
  vec3 c = (frame.pyramidViews[late] * vec4(s.xyz, 1.0)).xyz;
  float r = s.w * kOcclusionSlack, depth = -c.z;  // along the view direction
  if (depth - r <= znear) return false;            // reaches the near plane: nothing in front to test
  vec2 x = screenSpan(c.x, depth, r, scale.x), y = screenSpan(c.y, depth, r, scale.y);
  vec2 lo = vec2(x.x, y.x), hi = vec2(x.y, y.y);
  vec2 size = vec2(frame.viewportWidth, frame.viewportHeight);
  vec2 first = floor((lo * 0.5 + 0.5) * size), last = floor((hi * 0.5 + 0.5) * size);
  if (any(greaterThan(first, size - 1.0)) || any(lessThan(last, vec2(0.0)))) return false;  // off screen
  uvec2 p0 = uvec2(max(first, vec2(0.0))), p1 = uvec2(min(last, size - 1.0));
  // The level where the bounds span at most three texels each way: 2^(level + 1) >= the span in pixels
  // (at least level 1, the finest stored): 3 x 3 texels cover at most 1.5 times the bounds each way,
  // where 2 x 2 at the next level up cover up to twice.
  uint span = max(p1.x - p0.x, p1.y - p0.y);
  uint level = clamp(span <= 1u ? 0u : uint(findMSB(span - 1u)), 1u, frame.pyramidLevels - 1u);  // 0 not stored
  p0 >>= level;
  p1 >>= level;
  const uvec2 mid = min(p0 + 1u, p1);
  float farthest = min(min(pyramidRow(level, p0.x, mid.x, p1.x, p0.y), pyramidRow(level, p0.x, mid.x, p1.x, mid.y)),
                       pyramidRow(level, p0.x, mid.x, p1.x, p1.y));
  // Reversed depth: znear / distance, larger is nearer.
  return znear / (depth - r) * kOcclusionSlack < farthest;
}

// An object-space sphere of an instance, grown by an error where it is finite: a leaf drawn as patches
// lies off its triangles by up to its chord error, which its node's and group's errors bound.
bool sphereOccludedWithError(Instance inst, vec4 sphere, float error) {
  vec4 s = worldSphere(inst, sphere);
  if (frame.drawPatches != 0u && !isinf(error)) s.w += error * inst.maxScale;
  return sphereOccluded(s);
}

uint gOccludedNodes = 0u, gOccludedClusters = 0u;  // late pass (flushed with the traversal's statistics)

// Whether queue item `code` of `instance` (a node, a group, or a cluster as a run of one), bounded by the
// object-space sphere and error, is hidden: the early pass defers it to the late one, which drops it.
bool itemHidden(uint instance, uint code, Instance inst, vec4 sphere, float error) {
  if (!occlusionTests() || !sphereOccludedWithError(inst, sphere, error)) return false;
  if (passConstants.pass == VGEO_PASS_EARLY) {
    uint slot = atomicAdd(counters.deferredItems, 1u);
    if (slot < frame.queueCapacity) {
      deferredItems[2u * slot] = instance;
      deferredItems[2u * slot + 1u] = code;
    } else {
      atomicAdd(counters.queueOverflow, 1u);  // the frame is incomplete; the queue (and this list) grows
    }
  } else if ((code & VGEO_ITEM_RUN_BIT) != 0u) {
    gOccludedClusters++;
  } else {
    gOccludedNodes++;
  }
  return true;
}
