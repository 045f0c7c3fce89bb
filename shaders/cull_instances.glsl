// cull_instances.glsl: instance culling, shared by its own pass (cull_instances.comp) and by the persistent
// traversal, which culls small scenes itself (one instance a worker, no pass and barrier in front of it).
// An instance whose bounds meet the cull frustum counts as visible. The flat traversal gets it as
// (instance, root); for the others the BVH root's children (the simplification levels' subtrees, up to
// VGEO_BVH_ROOT_WIDTH) are tested and those that may hold drawn clusters are queued as (instance, node): the
// root is never a queue item.
// cullInstancesSpread: VGEO_CULL_INSTANCE_LANES lanes an instance (workgroups of VGEO_CULL_WORKGROUP lanes,
// defined by the includer) test the children side by side and the workgroup queues them with one
// reservation (one lane testing ~20 children in a row puts a chain of ~20 loads in front of the
// traversal). The root's children come from instanceRoots (shaderio_frame.h, SceneArrays),
// loaded beside the instance record, not from the geometry's root.
// Sweeps (persistent traversal): a kept level subtree whose clusters are one run may be queued as runs of
// up to VGEO_SWEEP_RUN clusters instead, tested in one step rather than down a chain of node steps. The
// workgroup claims the cluster tests of all its candidates from frame.sweepBudget with one atomic; when the
// budget cannot cover them, they are walked (and the slots reserved for their runs but the first are
// VGEO_ITEM_SKIP).

// The limit surface of a leaf drawn as patches lies off its vertices by up to its chord error, a small
// fraction of the mesh: occlusion tests instance bounds grown by this much.
const float kInstancePatchSlack = 1.01;

// Instance `instance`, when its bounds meet the cull frustum and the depth pyramid does not hide them.
// `occluded`: hidden (the caller defers it in the early pass, counts it in the late one).
bool instanceVisible(uint instance, out Instance inst, out Geometry g, out bool occluded) {
  occluded = false;
  if (instance >= frame.instanceCount) return false;
  inst = instances[instance];
  g = geometries[inst.geometry];
  vec4 s = worldSphere(inst, g.boundsSphere);
  s.w *= kPruneSlack;
  if (!sphereInFrustum(s)) return false;
  occluded = occlusionTests() && sphereOccluded(vec4(s.xyz, s.w * (frame.drawPatches != 0u ? kInstancePatchSlack : 1.0)));
  return !occluded;
}

// The workgroup's hidden instances: each counts itself in sHidden (reset by the workgroup's first lane
// before its first barrier), its number there `k`; then every lane calls deferHiddenInstances (barriers):
// the early pass lists them for the late pass (one reservation), the late pass counts them.
shared uint sHidden, sDeferredBase;
void deferHiddenInstances(bool occluded, uint k, uint instance) {
  barrier();  // every lane's count is in
  if (gl_LocalInvocationIndex == 0u && sHidden != 0u) {
    if (passConstants.pass == VGEO_PASS_EARLY) sDeferredBase = atomicAdd(counters.deferredInstances, sHidden);
    else atomicAdd(counters.occludedInstances, sHidden);
  }
  barrier();
  if (occluded && passConstants.pass == VGEO_PASS_EARLY) deferredInstances[sDeferredBase + k] = instance;
}

#ifndef VGEO_CULL_SERIAL
// The serial variant declares none of these shared arrays: unused, their ~14 KB a workgroup would still
// lower how many workgroups run at once.
const uint kCullInstances = uint(VGEO_CULL_WORKGROUP) / VGEO_CULL_INSTANCE_LANES;  // instances a workgroup
const uint kMaxKept = kCullInstances * VGEO_BVH_ROOT_WIDTH;
const uint kRunBits = 20u;  // sSwept: swept items << kRunBits | their runs
// Levels of more clusters are walked, so that a workgroup's runs stay under 2^kRunBits (kMaxKept levels of
// 65,536 clusters: 2^19 runs) and its tests under 2^32.
const uint kMaxSweptLevel = 65536u;
shared uint sVisible, sKept, sFirst, sWalked, sWalkedNodes, sSweepTests, sSweep, sSwept, sDropped;
shared uint sKeptInstance[kMaxKept], sKeptCode[kMaxKept], sKeptSlot[kMaxKept];
shared uint sKeptRunFirst[kMaxKept], sKeptRunCount[kMaxKept];  // the level's cluster run (count 0: none)
shared uint sSweptList[kMaxKept], sSweptStart[kMaxKept];  // swept items, and their first run in the reservation

// Instances [firstInstance, firstInstance + kCullInstances), by the whole workgroup (it has barriers).
// The node items it queues count in counters.nodesPending before they are written, so that a traversal
// running beside it cannot take one, finish it and bring the count to 0 first. `inTraversal`: called by a
// persistent worker, which the host counted in nodesPending (see the traversal's termination); it takes
// itself off once everything it queued is written.
void cullInstancesSpread(uint firstInstance, bool inTraversal) {
  const uint lane = gl_LocalInvocationIndex, lanes = VGEO_CULL_INSTANCE_LANES, part = lane % lanes;
  if (lane == 0u) {
    sVisible = 0u;
    sHidden = 0u;
    sKept = 0u;
    sWalked = 0u;
    sWalkedNodes = 0u;
    sSweepTests = 0u;
    sSweep = 0u;
    sSwept = 0u;
    sDropped = 0u;
  }
  barrier();
  uint instance = passInstance(firstInstance + lane / lanes);
  Instance inst;
  Geometry g;
  // The root beside the instance record, not after the geometry's (a load less in a row).
  const uvec2 root = instance < frame.instanceCount ? instanceRoots[instance] : uvec2(0u);
  bool occluded;
  const bool visible = instanceVisible(instance, inst, g, occluded);
  if (frame.queueRoots == 0u && visible) {
    const uint count = root.x & ~VGEO_NODE_LEAF_BIT;
    const bool leaf = (root.x & VGEO_NODE_LEAF_BIT) != 0u;
    for (uint i = part; i < count; i += lanes) {
      uint child = root.y + i;
      uvec2 run = frame.sweepBudget != 0u && !leaf ? levelClusterRuns[child] : uvec2(0u);
      if (run.y > kMaxSweptLevel) run = uvec2(0u);
      if (childMayHoldDrawn(instance, inst, child, leaf)) {
        uint k = atomicAdd(sKept, 1u);
        sKeptInstance[k] = instance;
        sKeptCode[k] = childItem(child, leaf);
        sKeptRunFirst[k] = run.x;
        sKeptRunCount[k] = run.y;
        if (run.y != 0u) {  // its runs, as if the sweep is granted (one shared atomic counts items and runs)
          atomicAdd(sSweepTests, run.y);
          uint counts = atomicAdd(sSwept, (1u << kRunBits) | ((run.y + VGEO_SWEEP_RUN - 1u) / VGEO_SWEEP_RUN));
          sSweptList[counts >> kRunBits] = k;
          sSweptStart[counts >> kRunBits] = counts & ((1u << kRunBits) - 1u);
        } else {
          sKeptSlot[k] = atomicAdd(sWalked, 1u);
          if (!leaf) atomicAdd(sWalkedNodes, 1u);
        }
      }
    }
  }
  const bool deferred = occluded && part == 0u;  // one lane an instance
  const uint hiddenIndex = deferred ? atomicAdd(sHidden, 1u) : 0u;
  if (visible && part == 0u) {
    atomicAdd(sVisible, 1u);
    if (frame.queueRoots != 0u) writeQueue(reserveQueue(1u), instance, g.nodeOffset);
    else gNodes++;
  }
  barrier();
  // The budget claim and the queue reservation together (two round trips in a row cost a view of a few
  // instances ~1 us): the reservation counts the runs, as if the claim is granted. When it is not, each
  // swept item is walked instead from its first run's slot, and its other runs' slots are skipped.
  const uint sweptItems = sSwept >> kRunBits, runs = sSwept & ((1u << kRunBits) - 1u);
  if (lane == 0u) {
    if (sVisible != 0u) atomicAdd(counters.visibleInstances, sVisible);
    uint claimed = 0u;
    if (sSweepTests != 0u) claimed = atomicAdd(counters.sweepTests, sSweepTests);
    if (runs + sWalked != 0u) {
      sFirst = reserveQueue(runs + sWalked);
      atomicMax(counters.cullItems, gQueueEnd);  // not waited on
    }
    sSweep = sSweepTests != 0u && claimed + sSweepTests <= frame.sweepBudget ? 1u : 0u;
    if (sSweep != 0u) atomicAdd(counters.sweptTests, sSweepTests);
    // Walked level subtrees are node items (a swept item always: a level subtree's root is a node); those
    // that fall past the queue's capacity are taken off again below.
    uint nodeItems = sWalkedNodes + (sSweep != 0u ? 0u : sweptItems);
    if (nodeItems != 0u) atomicAdd(counters.nodesPending, nodeItems);
  }
  barrier();
  // The reservation: the swept items' runs first, in sSweptList order, then one slot for each walked item.
  for (uint k = lane; k < sKept; k += uint(VGEO_CULL_WORKGROUP))
    if (sKeptRunCount[k] == 0u && !writeQueue(sFirst + runs + sKeptSlot[k], sKeptInstance[k], sKeptCode[k]) && (sKeptCode[k] & VGEO_ITEM_GROUP_BIT) == 0u)
      atomicAdd(sDropped, 1u);
  // Each lane writes a contiguous share of the runs, over all swept items at once: one search for its
  // first run, then along the items; not a search for every run (they come ~10 in a row in the heaviest
  // workgroup of a close view), nor the runs of one item spread over the lanes (far views have one run an
  // item), nor one lane writing an item's runs in a row (close views have many).
  const uint share = (runs + uint(VGEO_CULL_WORKGROUP) - 1u) / uint(VGEO_CULL_WORKGROUP);
  uint j = lane * share;
  const uint end = min(j + share, runs);
  if (j < end) {
    uint lo = 0u, hi = sweptItems - 1u;  // the last item whose runs start at or before j
    while (lo < hi) {
      uint mid = (lo + hi + 1u) / 2u;
      if (sSweptStart[mid] <= j) lo = mid;
      else hi = mid - 1u;
    }
    for (; j < end; j++) {
      while (lo + 1u < sweptItems && sSweptStart[lo + 1u] <= j) lo++;
      uint k = sSweptList[lo], r = j - sSweptStart[lo];
      if (sSweep != 0u) {
        uint length = min(VGEO_SWEEP_RUN, sKeptRunCount[k] - r * VGEO_SWEEP_RUN);
        writeQueue(sFirst + j, sKeptInstance[k] | ((length - 1u) << VGEO_RUN_INSTANCE_BITS), VGEO_ITEM_RUN_BIT | (sKeptRunFirst[k] + r * VGEO_SWEEP_RUN));
      } else if (r == 0u) {  // walked
        if (!writeQueue(sFirst + j, sKeptInstance[k], sKeptCode[k])) atomicAdd(sDropped, 1u);
      } else {
        writeQueue(sFirst + j, 0u, VGEO_ITEM_SKIP);
      }
    }
  }
  // In the traversal the runs must be seen before the count that lets the workers stop waiting for them.
  if (inTraversal) memoryBarrierBuffer();
  barrier();
  deferHiddenInstances(deferred, hiddenIndex, instance);
  const uint off = sDropped + (inTraversal ? 1u : 0u);
  if (lane == 0u && off != 0u) atomicAdd(counters.nodesPending, 0u - off);
}
#endif
