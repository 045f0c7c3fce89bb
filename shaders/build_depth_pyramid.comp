#version 450
// build_depth_pyramid.comp: the depth pyramid of the early pass's picture (shaderio_frame.h,
// VGEO_PYRAMID_*) in one dispatch, then the late pass begun (begin_late_pass.glsl); or of a one-pass
// frame's picture, for the next frame. Level k covers
// 2^k x 2^k pixels a texel and holds the farthest (smallest reversed) depth under it, so a texel never
// claims a depth nearer than any pixel it covers. Level 0, a pixel's own depth, is not stored: the tests
// start at level 1.
//   Each workgroup a 32 x 32 pixel tile: each lane reads 2 x 2 pixels, the nearest depth of each (the
//   visibility buffer's and the depth target's, whichever the frame drew into; 0 where neither holds
//   one), writes their farthest to level 1, and the workgroup reduces its 16 x 16 texels on to levels 2 to
//   frame.pyramidTileLevels (at most 5) in shared memory.
//   The last workgroup to finish its tile (counters.pyramidTilesDone; every tile's texels made visible
//   before it counts) builds the levels above, each from the one below, in shared memory once a level
//   fits there, and then begins the late pass.
// One dispatch, not one a level: every dispatch and barrier costs a GPU a few microseconds, and lavapipe
// pays for every barrier of its 256 lanes, so there the tile stops at level 1 and the last workgroup does
// the rest; a GPU takes the tile to level 5 (bench/occlusion.md).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 16, local_size_y = 16) in;
#include "common.glsl"
#include "begin_late_pass.glsl"

layout(set = 0, binding = VGEO_BINDING_DEPTH_PYRAMID, std430) coherent buffer DepthPyramidBuffer { float depthPyramid[]; };
// The visibility buffer's 64-bit words as pairs of 32-bit ones (no 64-bit types needed): the depth's bits
// are the high word's above bit VGEO_VISIBILITY_ID_BITS - 32.
layout(set = 0, binding = VGEO_BINDING_VISIBILITY, std430) readonly buffer VisibilityWords { uint visibilityWords[]; };
layout(set = 0, binding = VGEO_BINDING_DEPTH_IMAGE) uniform sampler2D depthImage;

shared float sTexels[16][16];

uvec2 levelSize(uint level) {
  uvec2 size = uvec2(frame.viewportWidth, frame.viewportHeight);
  return (size + (1u << level) - 1u) >> level;
}
uint levelOffset(uint level) { return frame.pyramidOffsets[level >> 2u][level & 3u]; }

float pixelDepth(uvec2 p) {
  const uvec2 size = levelSize(0u);
  p = min(p, size - 1u);  // past the edge: the edge pixel again, which changes no minimum
  float depth = 0.0;
  if ((frame.pyramidSources & VGEO_PYRAMID_FROM_VISIBILITY) != 0u)
    depth = uintBitsToFloat(visibilityWords[2u * (p.y * size.x + p.x) + 1u] >> (VGEO_VISIBILITY_ID_BITS - 32u));
  if ((frame.pyramidSources & VGEO_PYRAMID_FROM_DEPTH_IMAGE) != 0u) depth = max(depth, texelFetch(depthImage, ivec2(p), 0).r);
  return depth;
}

void writeTexel(uint level, uvec2 p, float depth) {
  const uvec2 size = levelSize(level);
  if (all(lessThan(p, size))) depthPyramid[levelOffset(level) + p.y * size.x + p.x] = depth;
}

// Levels 1 to frame.pyramidTileLevels of this workgroup's tile.
void reduceTile(uvec2 lane) {
  const uvec2 texel = gl_WorkGroupID.xy * 16u + lane, pixel = 2u * texel;
  float depth = min(min(pixelDepth(pixel), pixelDepth(pixel + uvec2(1u, 0u))),
                    min(pixelDepth(pixel + uvec2(0u, 1u)), pixelDepth(pixel + uvec2(1u))));
  writeTexel(1u, texel, depth);
  if (frame.pyramidTileLevels < 2u) return;  // the whole workgroup
  // A texel past level 1's edge repeats the edge texel (as the clamped reduction would), so the
  // reduction in shared memory below matches the one from the buffer above the tile's levels.
  sTexels[lane.y][lane.x] = depth;
  barrier();
  const uvec2 size1 = levelSize(1u), edge = min(texel, size1 - 1u) - gl_WorkGroupID.xy * 16u;
  depth = sTexels[edge.y][edge.x];
  barrier();
  sTexels[lane.y][lane.x] = depth;
  for (uint level = 2u, n = 8u; level <= frame.pyramidTileLevels && level < frame.pyramidLevels; level++, n /= 2u) {
    barrier();
    float reduced = 0.0;
    if (all(lessThan(lane, uvec2(n)))) {
      const uvec2 q = 2u * lane;
      reduced = min(min(sTexels[q.y][q.x], sTexels[q.y][q.x + 1u]), min(sTexels[q.y + 1u][q.x], sTexels[q.y + 1u][q.x + 1u]));
      writeTexel(level, gl_WorkGroupID.xy * n + lane, reduced);
    }
    barrier();
    if (all(lessThan(lane, uvec2(n)))) sTexels[lane.y][lane.x] = reduced;
  }
}

// A level of at most kSharedTexels texels, kept for the next: its reads cost no trip to memory.
const uint kSharedTexels = 1024u;
shared float sLevel[kSharedTexels];

// Texel p of `level` from the four of the level below (clamped at its edge), read from sLevel when the
// level below is kept there.
float reduceFromBelow(uint level, uvec2 p, bool belowShared) {
  const uvec2 below = levelSize(level - 1u), q0 = min(2u * p, below - 1u), q1 = min(2u * p + 1u, below - 1u);
  if (belowShared)
    return min(min(sLevel[q0.y * below.x + q0.x], sLevel[q0.y * below.x + q1.x]),
               min(sLevel[q1.y * below.x + q0.x], sLevel[q1.y * below.x + q1.x]));
  const uint base = levelOffset(level - 1u);
  return min(min(depthPyramid[base + q0.y * below.x + q0.x], depthPyramid[base + q0.y * below.x + q1.x]),
             min(depthPyramid[base + q1.y * below.x + q0.x], depthPyramid[base + q1.y * below.x + q1.x]));
}

// The levels above the tiles', by the last workgroup; a level that fits sLevel is kept there (a lane
// holds at most kSharedTexels / 256 of its texels).
void reduceTop() {
  const uint index = gl_LocalInvocationIndex;
  bool belowShared = false;
  for (uint level = frame.pyramidTileLevels + 1u; level < frame.pyramidLevels; level++) {
    const uvec2 size = levelSize(level);
    const uint count = size.x * size.y;
    float kept[kSharedTexels / 256u];
    for (uint t = index, k = 0u; t < count; t += 256u, k++) {
      const float depth = reduceFromBelow(level, uvec2(t % size.x, t / size.x), belowShared);
      writeTexel(level, uvec2(t % size.x, t / size.x), depth);
      if (k < kSharedTexels / 256u) kept[k] = depth;
    }
    barrier();  // every read of the level below done
    belowShared = count <= kSharedTexels;
    if (belowShared)
      for (uint t = index, k = 0u; t < count; t += 256u, k++) sLevel[t] = kept[k];
    else
      memoryBarrierBuffer();
    barrier();
  }
}

shared bool sLastTile;

void main() {
  reduceTile(gl_LocalInvocationID.xy);
  // Every tile's texels visible before it counts; the last to count sees them all.
  memoryBarrierBuffer();
  barrier();
  if (gl_LocalInvocationIndex == 0u)
    sLastTile = atomicAdd(counters.pyramidTilesDone, 1u) == gl_NumWorkGroups.x * gl_NumWorkGroups.y - 1u;
  barrier();
  if (!sLastTile) return;  // the whole workgroup
  memoryBarrierBuffer();
  reduceTop();
  // After a one-pass frame the pyramid is only for the next frame's early pass (occlusion_policy.h).
  if (gl_LocalInvocationIndex == 0u && passConstants.pass != VGEO_PASS_ONLY) beginLatePass();
}
