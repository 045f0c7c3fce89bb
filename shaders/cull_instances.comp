#version 450
// cull_instances.comp: frame.cullInstanceLanes lanes an instance. An instance whose bounds meet the cull
// frustum counts as visible. The flat traversal gets it as (instance, root); for the others the BVH root's
// children (the simplification levels' subtrees, up to VGEO_BVH_ROOT_WIDTH) are tested here and those that
// may hold drawn clusters are queued as (instance, node): the root is never a queue item. With one lane an
// instance each lane queues its own; with VGEO_CULL_INSTANCE_LANES the lanes test the children side by
// side and the workgroup queues them with one reservation (one lane testing ~20 children in a row put a
// chain of ~20 loads in front of the traversal: 10-18% of a close view's selection on an H100).
// Sweeps (persistent traversal, spread culling): a kept level subtree whose clusters are one run may be
// queued as runs of up to VGEO_SWEEP_RUN clusters instead, tested in one step rather than down a chain of
// node steps. The workgroup claims the cluster tests of all its candidates from frame.sweepBudget with one
// atomic; when the budget cannot cover them, they are walked.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;
#include "common.glsl"
#include "traverse_common.glsl"

const uint kSpreadInstances = 64u / VGEO_CULL_INSTANCE_LANES;  // per workgroup, when spread
const uint kMaxKept = kSpreadInstances * VGEO_BVH_ROOT_WIDTH;
shared uint sVisible, sKept, sFirst, sSlots, sSweepTests, sSweep, sSwept, sPending;
shared uint sKeptInstance[kMaxKept], sKeptCode[kMaxKept], sKeptSlot[kMaxKept];
shared uint sKeptRunFirst[kMaxKept], sKeptRunCount[kMaxKept];  // the level's cluster run (count 0: none)
shared uint sSweptList[kMaxKept];  // kept items written as runs
layout(set = 0, binding = 22, std430) readonly buffer LevelRunBuffer { uvec2 levelClusterRuns[]; };

// Kept item k is swept: its workgroup's claim on the budget was granted and its clusters are one run.
bool swept(uint k) { return sSweep != 0u && sKeptRunCount[k] != 0u; }

void main() {
  beginStats();
  const uint lane = gl_LocalInvocationIndex, lanes = frame.cullInstanceLanes, part = lane % lanes;
  if (lane == 0u) {
    sVisible = 0u;
    sKept = 0u;
    sSlots = 0u;
    sSweepTests = 0u;
    sSweep = 0u;
    sSwept = 0u;
    sPending = 0u;
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
        uint queuedNodes = processItem(instance, g.nodeOffset);
        if (queuedNodes != 0u) atomicAdd(sPending, queuedNodes);
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
            uvec2 run = frame.sweepBudget != 0u && !leaf ? levelClusterRuns[child] : uvec2(0u);
            sKeptRunFirst[k] = run.x;
            sKeptRunCount[k] = run.y;
            if (run.y != 0u) atomicAdd(sSweepTests, run.y);
          }
        }
      }
    }
  }
  barrier();
  if (lane == 0u) {
    if (sVisible != 0u) atomicAdd(counters.visibleInstances, sVisible);
    if (sSweepTests != 0u) {
      uint claimed = atomicAdd(counters.sweepTests, sSweepTests);
      sSweep = claimed + sSweepTests <= frame.sweepBudget ? 1u : 0u;
      if (sSweep != 0u) atomicAdd(counters.sweptTests, sSweepTests);
    }
  }
  barrier();
  // Each kept item's first slot in the workgroup's reservation (order within it does not matter): its runs
  // when swept, else one.
  for (uint k = lane; k < sKept; k += 64u) {
    sKeptSlot[k] = atomicAdd(sSlots, swept(k) ? (sKeptRunCount[k] + VGEO_SWEEP_RUN - 1u) / VGEO_SWEEP_RUN : 1u);
    if (swept(k)) sSweptList[atomicAdd(sSwept, 1u)] = k;
  }
  barrier();
  if (lane == 0u && sSlots != 0u) sFirst = reserveQueue(sSlots);
  barrier();
  for (uint k = lane; k < sKept; k += 64u)
    if (!swept(k) && writeQueue(sFirst + sKeptSlot[k], sKeptInstance[k], sKeptCode[k]) && (sKeptCode[k] & VGEO_ITEM_GROUP_BIT) == 0u)
      atomicAdd(sPending, 1u);
  // A swept level's runs (up to ~160 for a million-triangle mesh's finest level) by all lanes together
  // (with one lane writing each level's runs in a row, sweeps made a 100-instance close view's culling
  // 0.029 instead of 0.020 ms on an H100).
  for (uint i = 0u; i < sSwept; i++) {
    uint k = sSweptList[i], first = sFirst + sKeptSlot[k];
    for (uint r = lane; r * VGEO_SWEEP_RUN < sKeptRunCount[k]; r += 64u) {
      uint length = min(VGEO_SWEEP_RUN, sKeptRunCount[k] - r * VGEO_SWEEP_RUN);
      writeQueue(first + r, sKeptInstance[k] | ((length - 1u) << VGEO_RUN_INSTANCE_BITS), VGEO_ITEM_RUN_BIT | (sKeptRunFirst[k] + r * VGEO_SWEEP_RUN));
    }
  }
  barrier();
  if (lane == 0u && sPending != 0u) atomicAdd(counters.nodesPending, sPending);
  flushStats();
}
