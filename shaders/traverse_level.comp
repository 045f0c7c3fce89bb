#version 450
// traverse_level.comp: one dispatch per hierarchy depth. Processes the queue window
// [levelStart, levelEnd) that prepare_level.comp set from what the previous dispatch produced.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
layout(local_size_x = VGEO_TRAVERSAL_WORKGROUP) in;
#include "traverse_common.glsl"

void main() {
  beginStats();
  uint slot = counters.levelStart + gl_GlobalInvocationID.x;
  uint instance, code;
  if (slot < counters.levelEnd && takeQueue(slot, instance, code)) {
    processItem(instance, code);
    atomicAdd(counters.itemsDone, 1u);
  }
  flushStats();
}
