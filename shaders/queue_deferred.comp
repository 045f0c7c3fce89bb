#version 450
// queue_deferred.comp: the late pass's first items, 64 a workgroup: the queue items the early pass deferred
// (occlusion.glsl), queued as they are (a workgroup's with one reservation) and their node items counted
// pending before the traversal starts (its termination, traverse_persistent.comp).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
layout(local_size_x = 64) in;
#include "traverse_common.glsl"

shared uint sFirst, sDeferredNodes;

void main() {
  const uint deferred = min(counters.deferredItems, frame.queueCapacity), first = gl_WorkGroupID.x * 64u;
  const uint lane = gl_LocalInvocationIndex, count = min(64u, deferred - first);
  if (lane == 0u) {
    sFirst = reserveQueue(count);
    sDeferredNodes = 0u;
  }
  barrier();
  if (lane < count) {
    const uint instance = deferredItems[2u * (first + lane)], code = deferredItems[2u * (first + lane) + 1u];
    const bool node = (code & (VGEO_ITEM_GROUP_BIT | VGEO_ITEM_RUN_BIT)) == 0u;
    if (writeQueue(sFirst + lane, instance, code) && node) atomicAdd(sDeferredNodes, 1u);
  }
  barrier();
  if (lane == 0u && sDeferredNodes != 0u) atomicAdd(counters.nodesPending, sDeferredNodes);
}
