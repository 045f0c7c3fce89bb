#version 450
// cull_instances.comp: instance culling in a pass of its own (cull_instances.glsl tells what it does).
// Two variants (two pipelines):
//   VGEO_CULL_SERIAL: one lane an instance, queueing its own (large scenes, lavapipe).
//   otherwise cullInstancesSpread, VGEO_CULL_INSTANCE_LANES lanes an instance in workgroups of
//     VGEO_CULL_SPREAD_WORKGROUP.
// In the late pass of a frame with occlusion culling, each workgroup first queues its share of the items
// the early pass deferred (queue_deferred.glsl): one dispatch and barrier less in front of the traversal.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#ifdef VGEO_CULL_SERIAL
#define VGEO_CULL_WORKGROUP VGEO_CULL_SERIAL_WORKGROUP
layout(local_size_x = VGEO_CULL_WORKGROUP) in;
#else
#define VGEO_CULL_WORKGROUP VGEO_CULL_SPREAD_WORKGROUP
layout(local_size_x = VGEO_CULL_WORKGROUP) in;
#endif
#include "traverse_common.glsl"
#include "cull_instances.glsl"
#include "queue_deferred.glsl"

#ifdef VGEO_CULL_SERIAL
shared uint sVisible, sPending, sQueueEnd;

void main() {
  if (passConstants.pass == VGEO_PASS_LATE) queueDeferredItems(gl_WorkGroupID.x, VGEO_CULL_WORKGROUP);
  beginStats();
  if (gl_LocalInvocationIndex == 0u) {
    sVisible = 0u;
    sHidden = 0u;
    sPending = 0u;
    sQueueEnd = 0u;
  }
  barrier();
  uint instance = passInstance(gl_GlobalInvocationID.x);
  Instance inst;
  Geometry g;
  bool occluded;
  if (instanceVisible(instance, inst, g, occluded)) {
    atomicAdd(sVisible, 1u);
    if (frame.queueRoots != 0u) {
      writeQueue(reserveQueue(1u), instance, g.nodeOffset);
    } else {
      uint queuedNodes = processItem(instance, g.nodeOffset);
      if (queuedNodes != 0u) atomicAdd(sPending, queuedNodes);
      if (gQueueEnd != 0u) atomicMax(sQueueEnd, gQueueEnd);
    }
  }
  const uint hiddenIndex = occluded ? atomicAdd(sHidden, 1u) : 0u;
  deferHiddenInstances(occluded, hiddenIndex, instance);
  if (gl_LocalInvocationIndex == 0u) {
    if (sVisible != 0u) atomicAdd(counters.visibleInstances, sVisible);
    if (sPending != 0u) atomicAdd(counters.nodesPending, sPending);
    if (sQueueEnd != 0u) atomicMax(counters.cullItems, sQueueEnd);  // not waited on
  }
  flushStats();
}
#else
void main() {
  if (passConstants.pass == VGEO_PASS_LATE) queueDeferredItems(gl_WorkGroupID.x, VGEO_CULL_WORKGROUP);
  beginStats();
  cullInstancesSpread(gl_WorkGroupID.x * kCullInstances, false);
  flushStats();
}
#endif
