#version 450
// cull_instances.comp: one thread per instance; instances whose bounds meet the cull frustum queue
// (instance, BVH root) for the traversal.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
#include "common.glsl"
#include "traverse_common.glsl"

void main() {
  uint instance = gl_GlobalInvocationID.x;
  if (instance >= frame.instanceCount) return;
  Instance inst = instances[instance];
  Geometry g = geometries[inst.geometry];
  vec4 s = worldSphere(inst, g.boundsSphere);
  s.w *= kPruneSlack;
  if (!sphereInFrustum(s)) return;
  atomicAdd(counters.visibleInstances, 1u);
  writeQueue(reserveQueue(1u), instance, g.nodeOffset);
}
