#version 450
// cull_instances.comp: frame.cullInstanceLanes lanes an instance. An instance whose bounds meet the cull
// frustum counts as visible. The flat traversal gets it as (instance, root); for the others the BVH root's
// children (the simplification levels' subtrees, up to VGEO_BVH_ROOT_WIDTH) are tested here and those that
// may hold drawn clusters are queued as (instance, node): the root is never a queue item. With one lane an
// instance each lane queues its own; with VGEO_CULL_INSTANCE_LANES the lanes test the children side by
// side and the workgroup queues them with one reservation (one lane testing ~20 children in a row put a
// chain of ~20 loads in front of the traversal: 10-18% of a close view's selection on an H100).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
#include "common.glsl"
#include "traverse_common.glsl"

const uint kSpreadInstances = 64u / VGEO_CULL_INSTANCE_LANES;  // per workgroup, when spread
shared uint sVisible, sKept, sFirst;
shared uint sKeptInstance[kSpreadInstances * VGEO_BVH_ROOT_WIDTH], sKeptCode[kSpreadInstances * VGEO_BVH_ROOT_WIDTH];

void main() {
  beginStats();
  const uint lane = gl_LocalInvocationIndex, lanes = frame.cullInstanceLanes, part = lane % lanes;
  if (lane == 0u) {
    sVisible = 0u;
    sKept = 0u;
  }
  barrier();
  uint instance = gl_WorkGroupID.x * (64u / lanes) + lane / lanes;
  if (instance < frame.instanceCount) {
    Instance inst = instances[instance];
    Geometry g = geometries[inst.geometry];
    vec4 s = worldSphere(inst, g.boundsSphere);
    s.w *= kPruneSlack;
    if (sphereInFrustum(s)) {
      if (part == 0u) atomicAdd(sVisible, 1u);
      if (frame.queueRoots != 0u) {
        if (part == 0u) writeQueue(reserveQueue(1u), instance, g.nodeOffset);
      } else if (lanes == 1u) {
        processItem(instance, g.nodeOffset);
      } else {
        BvhNode root = nodes[g.nodeOffset];
        uint count = root.childCountAndFlags & ~VGEO_NODE_LEAF_BIT;
        bool leaf = (root.childCountAndFlags & VGEO_NODE_LEAF_BIT) != 0u;
        if (part == 0u) gNodes++;
        for (uint i = part; i < count; i += lanes) {
          uint child = root.childOffset + i;
          if (childMayHoldDrawn(inst, child, leaf)) {
            uint k = atomicAdd(sKept, 1u);
            sKeptInstance[k] = instance;
            sKeptCode[k] = childItem(child, leaf);
          }
        }
      }
    }
  }
  barrier();
  if (lane == 0u) {
    if (sVisible != 0u) atomicAdd(counters.visibleInstances, sVisible);
    if (sKept != 0u) sFirst = reserveQueue(sKept);
  }
  barrier();
  for (uint k = lane; k < sKept; k += 64u) writeQueue(sFirst + k, sKeptInstance[k], sKeptCode[k]);
  flushStats();
}
