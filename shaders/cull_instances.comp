#version 450
// cull_instances.comp: instance culling in a pass of its own (cull_instances.glsl tells what it does).
// Two variants (two pipelines):
//   VGEO_CULL_SERIAL: one lane an instance, queueing its own (large scenes, lavapipe).
//   otherwise cullInstancesSpread, VGEO_CULL_INSTANCE_LANES lanes an instance in workgroups of
//     VGEO_CULL_SPREAD_WORKGROUP.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#ifdef VGEO_CULL_SERIAL
layout(local_size_x = 64) in;
#else
#define VGEO_CULL_WORKGROUP VGEO_CULL_SPREAD_WORKGROUP
layout(local_size_x = VGEO_CULL_WORKGROUP) in;
#endif
#include "traverse_common.glsl"
#include "cull_instances.glsl"

#ifdef VGEO_CULL_SERIAL
shared uint sVisible, sPending, sQueueEnd;

void main() {
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
  beginStats();
  cullInstancesSpread(gl_WorkGroupID.x * kCullInstances, false);
  flushStats();
}
#endif
