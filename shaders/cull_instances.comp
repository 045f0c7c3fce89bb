#version 450
// cull_instances.comp: one thread per instance; instances whose bounds meet the cull frustum queue
// (instance, BVH root) for the traversal.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
#include "common.glsl"
#include "traverse_common.glsl"

shared uint sVisible;

void main() {
  if (gl_LocalInvocationIndex == 0u) sVisible = 0u;
  barrier();
  uint instance = gl_GlobalInvocationID.x;
  if (instance < frame.instanceCount) {
    Instance inst = instances[instance];
    Geometry g = geometries[inst.geometry];
    vec4 s = worldSphere(inst, g.boundsSphere);
    s.w *= kPruneSlack;
    if (sphereInFrustum(s)) {
      atomicAdd(sVisible, 1u);
      writeQueue(reserveQueue(1u), instance, g.nodeOffset);
    }
  }
  barrier();
  if (gl_LocalInvocationIndex == 0u && sVisible != 0u) atomicAdd(counters.visibleInstances, sVisible);
}
