#version 450
// reset_flat.comp: after the flat traversal, which reads the visible instances from the first queue
// slots without taking them, puts those slots back to unwritten and counts them done. Its first
// invocation writes the draw arguments (the draw list is final after the traversal's barrier).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
#include "common.glsl"
#include "draw_arguments.glsl"

void main() {
  uint slot = counters.queueBase + gl_GlobalInvocationID.x;
  if (gl_GlobalInvocationID.x == 0u) writeDrawArguments();
  if (gl_GlobalInvocationID.x >= counters.visibleInstances || slot >= frame.queueCapacity) return;
  queue[2 * slot] = VGEO_INVALID;
  queue[2 * slot + 1] = VGEO_INVALID;
  atomicAdd(counters.itemsDone, 1u);
}
