#version 450
// traverse_persistent.comp: persistent-thread traversal (docs/design.md, "Persistent threads without
// deadlock"). A fixed set of workgroups drains one global queue until it is empty and no item is in
// flight. Control flow around the queue is uniform: lane 0 claims for the workgroup and broadcasts
// through shared memory; no lane ever spins on a flag another lane of its workgroup must set.
//
// Claiming (frame.claimMode):
//   VGEO_CLAIM_PAST_FRONTIER (GPUs): one atomicAdd claims a batch of slots, produced or not; each lane keeps
//      its slot until a producer fills it. The batch follows the backlog (the items written and not yet
//      claimed, read beside the previous iteration's slots, shared over the workgroups), from kMinBatch
//      (a chain of single items, as in a close view of a few instances: spread over many workgroups) to
//      64 (100,000 instances: fewer claims). The first claim, which nothing has been read for, is sized
//      by the last frame's instance-culling items (frame.firstClaimItems), not the instance count, so that
//      a few workgroups do not take every item of a close view.
//   VGEO_CLAIM_WRITTEN (lavapipe): the lanes find the written prefix after the read position and
//      lane 0 claims it by compare-and-swap; nobody waits on a slot, a workgroup holds nothing between
//      iterations, so it can leave on the iteration budget (lavapipe ends loops silently after 65,535
//      iterations per invocation, all loops counted, docs/gpu-notes.md, 1: every loop here counts into gLoops).
// Termination: only node items (and workers culling instances, frame.cullInTraversal) produce items, and
// counters.nodesPending counts those queued or culling and not yet finished (a producer adds its children
// before it takes itself off, on the same counter). At 0 nothing more will be written: every slot below the
// last reservation is then visible (instance culling's, before this dispatch or before its worker left the
// count) or was a node item, taken already. So a worker that sees 0 lets go of the slots it holds
// unfilled and leaves: they lie past the end, and every item before them is claimed: one load, read beside
// the slots. A worker that sees 0 and as many slots claimed as reserved leaves after the
// items it took, without claiming again: every item is claimed, whatever order the three loads took
// effect in (the items reserved after its load of queueWrite were node items, all taken by the time
// nodesPending read 0). The constants' measurements: bench/README.md, cut selection.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_EXT_control_flow_attributes : require
#ifdef VGEO_PROFILE
#extension GL_EXT_shader_realtime_clock : require
#endif
#include "common.glsl"
layout(local_size_x = VGEO_TRAVERSAL_WORKGROUP) in;
#include "traverse_common.glsl"
#define VGEO_CULL_WORKGROUP VGEO_TRAVERSAL_WORKGROUP
#include "cull_instances.glsl"
#include "draw_arguments.glsl"

const uint kMinBatch = 4u;         // the least claim: a close view's chain of single items spreads over workers
const uint kSerialBatch = 32u;     // batches this large are tested a lane an item (see takeItemSerial)

shared uint sBase;     // first slot of the batch claimed this iteration
shared uint sCount;    // slots claimed this iteration (0: none)
shared uint sExit;     // kWorkerStays, or why the worker leaves after this claim
const uint kWorkerStays = 0u;
const uint kWorkerDone = 1u;          // every item is claimed and none will be written (see Termination)
const uint kWorkerOutOfBudget = 2u;   // lavapipe: the iteration budget is spent (frame.iterationBudget)
shared uint sHolding;  // lanes still holding a slot (claim mode 0)
shared uint sLoops;    // loop iterations so far, as lavapipe counts them (see below)
shared uint sRound;    // the most inner-loop iterations any lane ran this iteration
shared uint sRead, sReserved, sWritten, sClaiming;  // claim mode 1
shared uint sDone;     // items this workgroup finished this iteration (added to itemsDone once)
shared uint sDoneNodes;  // of those, node items (taken off counters.nodesPending once)
shared uint sFinal;    // claim mode 0, read beside this iteration's take:
const uint kMoreMayCome = 0u;    //   node items pending: a slot not yet written may still be
const uint kNoMoreWritten = 1u;  //   none pending: a slot not written now never will be
const uint kAllClaimed = 2u;     //   and every reserved slot is claimed: leave after these items
shared uint sLetGo;    // claim mode 0: a slot was let go as past the end (then the worker leaves)
shared uint sBatch;    // claim mode 0: slots the next claim takes
shared uint sNoItems;  // claim mode 0: instance culling queued nothing (read beside the first claim)
const uint kWatchLane = VGEO_TRAVERSAL_WORKGROUP - 1u;  // reads the counters while lanes from 0 take slots

// The work of an iteration is spread over all lanes, one test a lane, in two rounds (a chain of
// dependent steps is what a close view of a few instances waits through; one lane testing a node's
// children or a group's clusters in a row made every step several loads long):
//   round 1: the taken items' entries: a node's children (nodes, or groups for a leaf node), a group
//            item's clusters. Child nodes that may hold drawn clusters are kept and queued together (one
//            reservation a workgroup); child groups that may become round-2 entries at once, so a group
//            is never a queue item of its own (one step less).
//   round 2: those groups' clusters, tested with the cut rule.
// An entry is (instance, first child, kind), its tests numbered from sEntryStart[e]; test k belongs to the
// last entry starting at or before k. Entries are added with one shared atomic that counts entries (high
// bits) and tests (low bits) together, so entry order is start order.
const uint kNodeChildren = 0u, kGroupChildren = 1u, kClusters = 2u;
const uint kTestBits = 20u;  // tests a round < 2^20: VGEO_TRAVERSAL_WORKGROUP * VGEO_BVH_WIDTH * VGEO_MAX_GROUP_CLUSTERS
const uint kRound2 = VGEO_TRAVERSAL_WORKGROUP;  // round 2's entries follow round 1's (at most one per item)
const uint kMaxEntries = VGEO_TRAVERSAL_WORKGROUP + VGEO_TRAVERSAL_WORKGROUP * VGEO_BVH_WIDTH;
shared uint sEntryCounts[2];  // per round: entries << kTestBits | tests
shared uint sEntryInstance[kMaxEntries], sEntryFirst[kMaxEntries], sEntryStart[kMaxEntries], sEntryKind[kMaxEntries];

// Adds `value` to a shared counter for the calling lanes of a subgroup with one atomic (lanes adding to
// one shared address one by one serialize); `result` is the counter's value before this lane's part.
#define SUBGROUP_ATOMIC_ADD(counter, value, result) { \
  uint prefix_ = subgroupExclusiveAdd(value), total_ = subgroupAdd(value), base_ = 0u; \
  if (subgroupElect() && total_ != 0u) base_ = atomicAdd(counter, total_); \
  result = subgroupBroadcastFirst(base_) + prefix_; }

// Child nodes to queue, kept in round 1 and written after one reservation.
shared uint sKeepCount, sKeepFirst;
shared uint sKeepInstance[VGEO_TRAVERSAL_WORKGROUP * VGEO_BVH_WIDTH], sKeepCode[VGEO_TRAVERSAL_WORKGROUP * VGEO_BVH_WIDTH];

void keepItem(uint instance, uint code) {
  uint k;
  SUBGROUP_ATOMIC_ADD(sKeepCount, 1u, k);
  sKeepInstance[k] = instance;
  sKeepCode[k] = code;
}

// Every lane, after the barrier that follows the last keepItem.
void queueKept(uint lane) {
  if (lane == 0u) {
    sKeepFirst = reserveQueue(sKeepCount);
    // Before this workgroup takes its own items off (the end of the iteration, the same lane and counter).
    atomicAdd(counters.nodesPending, slotsKept(sKeepFirst, sKeepCount));
  }
  barrier();
  for (uint k = lane; k < sKeepCount; k += VGEO_TRAVERSAL_WORKGROUP) {
    gLoops++;
    writeQueue(sKeepFirst + k, sKeepInstance[k], sKeepCode[k]);
  }
}

// lavapipe's loop count (see main): the most loop iterations any lane ran this iteration. Uniform.
void noteLoops() {
  if (frame.iterationBudget != 0u) atomicMax(sRound, gLoops);
}

void addEntry(uint round, uint instance, uint first, uint tests, uint kind) {
  uint counts;
  SUBGROUP_ATOMIC_ADD(sEntryCounts[round], (1u << kTestBits) | tests, counts);
  uint e = (round == 0u ? 0u : kRound2) + (counts >> kTestBits);
  sEntryInstance[e] = instance;
  sEntryFirst[e] = first;
  sEntryStart[e] = counts & ((1u << kTestBits) - 1u);
  sEntryKind[e] = kind;
}

// A run or group item becomes an entry of `round` of its clusters, tested with the cut rule: a sweep run
// (cull_instances.comp) as it is, a group from its record; a skipped slot, nothing. False for a node item.
bool addClusterItem(uint round, uint instance, uint code) {
  if (code == VGEO_ITEM_SKIP) return true;
  if ((code & (VGEO_ITEM_GROUP_BIT | VGEO_ITEM_RUN_BIT)) == VGEO_ITEM_RUN_BIT) {
    addEntry(round, instance & ((1u << VGEO_RUN_INSTANCE_BITS) - 1u), code & ~VGEO_ITEM_RUN_BIT, (instance >> VGEO_RUN_INSTANCE_BITS) + 1u, kClusters);
    return true;
  }
  if ((code & VGEO_ITEM_GROUP_BIT) == 0u) return false;
  gNodes++;
  Group g = groups[code & ~VGEO_ITEM_GROUP_BIT];
  addEntry(round, instance, g.clusterOffset, g.clusterCount, kClusters);
  return true;
}

// A taken queue item becomes a round-1 entry. Returns whether it is a node item.
bool takeItem(uint instance, uint code) {
  if (addClusterItem(0u, instance, code)) return false;
  gNodes++;
  BvhNode node = nodes[code];
  bool leaf = (node.childCountAndFlags & VGEO_NODE_LEAF_BIT) != 0u;
  addEntry(0u, instance, node.childOffset, node.childCountAndFlags & ~VGEO_NODE_LEAF_BIT, leaf ? kGroupChildren : kNodeChildren);
  return true;
}

// A child of an entry, whoever tests it. Returns the draw-list code of a cluster to draw, or VGEO_INVALID.
uint testChild(uint instance, uint child, uint kind) {
  if (kind == kClusters) {
    return cutCluster(instance, child);
  } else if (kind == kGroupChildren) {
    Group g = groups[child];
    if (mayHoldDrawn(instance, child | VGEO_ITEM_GROUP_BIT, instances[instance], g.sphere, g.error)) {
      gNodes++;
      addEntry(1u, instance, g.clusterOffset, g.clusterCount, kClusters);
    }
  } else if (childMayHoldDrawn(instance, instances[instance], child, false)) {
    keepItem(instance, child);
  }
  return VGEO_INVALID;
}

// A taken item whose children its own lane tests, for large batches (100,000 instances): spreading them
// costs more than it saves once every lane has an item.
bool takeItemSerial(uint instance, uint code) {
  if (addClusterItem(1u, instance, code)) return false;
  gNodes++;
  BvhNode node = nodes[code];
  uint count = node.childCountAndFlags & ~VGEO_NODE_LEAF_BIT;
  uint kind = (node.childCountAndFlags & VGEO_NODE_LEAF_BIT) != 0u ? kGroupChildren : kNodeChildren;
  for (uint i = 0u; i < count; i++) {
    gLoops++;
    testChild(instance, node.childOffset + i, kind);  // node or group children: nothing to draw
  }
  return true;
}

// The entry of test k: the last of entries [base, base + entries) starting at or before k.
uint entryOf(uint base, uint entries, uint k) {
  uint lo = base, hi = base + entries - 1u;
  while (lo < hi) {
    gLoops++;
    uint mid = (lo + hi + 1u) / 2u;
    if (sEntryStart[mid] <= k) lo = mid;
    else hi = mid - 1u;
  }
  return lo;
}

// Every lane calls it after a barrier, with the round's entry count uniform and non-zero. A lane runs
// kLaneTests tests before it appends what they drew, with one draw-list atomic a subgroup: an atomic
// after every test would put its round trip between each test and the next. A specialization constant
// (VGEO_SPEC_LANE_TESTS): 4 on GPUs, 1 on lavapipe, which runs a lane's arrays of 4 slower.
layout(constant_id = VGEO_SPEC_LANE_TESTS) const uint kLaneTests = 4u;
void runRound(uint round, uint lane) {
  const uint base = round == 0u ? 0u : kRound2;
  const uint entries = sEntryCounts[round] >> kTestBits;
  const uint tests = sEntryCounts[round] & ((1u << kTestBits) - 1u);
  for (uint first = lane; first < tests; first += kLaneTests * VGEO_TRAVERSAL_WORKGROUP) {
    gLoops++;
    uint drawInstance[kLaneTests], draw[kLaneTests], drawn = 0u;
    for (uint t = 0u; t < kLaneTests; t++) {
      gLoops++;
      uint k = first + t * VGEO_TRAVERSAL_WORKGROUP;
      draw[t] = VGEO_INVALID;
      if (k >= tests) continue;
      uint e = entryOf(base, entries, k);
      drawInstance[t] = sEntryInstance[e];
      draw[t] = testChild(drawInstance[t], sEntryFirst[e] + k - sEntryStart[e], sEntryKind[e]);
      if (draw[t] != VGEO_INVALID) drawn++;
    }
    uint index;
    SUBGROUP_ATOMIC_ADD(counters.drawCount, drawn, index);
    for (uint t = 0u; t < kLaneTests; t++) {
      gLoops++;
      if (draw[t] != VGEO_INVALID) writeDraw(index++, drawInstance[t], draw[t]);
    }
  }
  noteLoops();
  barrier();
}

// runRound for a round of cluster entries only (sweep runs, groups' clusters): a lane loads the records
// of all its tests (instance, cluster, cone) before the first, so that they go out together, where
// runRound's tests of a lane run one after another. Only where some lane has more than one test and
// batches are small (see main): in rounds of one test a lane the extra registers cost more than the
// overlap gains. Its own function: a uniform flag of runRound costs the other rounds registers.
void runClusterRound(uint round, uint lane) {
  const uint base = round == 0u ? 0u : kRound2;
  const uint entries = sEntryCounts[round] >> kTestBits;
  const uint tests = sEntryCounts[round] & ((1u << kTestBits) - 1u);
  for (uint first = lane; first < tests; first += kLaneTests * VGEO_TRAVERSAL_WORKGROUP) {
    gLoops++;
    uint drawInstance[kLaneTests], child[kLaneTests], draw[kLaneTests], drawn = 0u;
    [[unroll]] for (uint t = 0u; t < kLaneTests; t++) {
      gLoops++;
      uint k = first + t * VGEO_TRAVERSAL_WORKGROUP;
      child[t] = VGEO_INVALID;
      drawInstance[t] = 0u;
      if (k >= tests) continue;
      uint e = entryOf(base, entries, k);
      drawInstance[t] = sEntryInstance[e];
      child[t] = sEntryFirst[e] + k - sEntryStart[e];
    }
    Instance inst[kLaneTests];
    Cluster cluster[kLaneTests];
    ClusterCone cone[kLaneTests];
    [[unroll]] for (uint t = 0u; t < kLaneTests; t++) {
      if (child[t] == VGEO_INVALID) continue;
      inst[t] = instances[drawInstance[t]];
      cluster[t] = clusters[child[t]];
      cone[t] = clusterCones[child[t]];
    }
    [[unroll]] for (uint t = 0u; t < kLaneTests; t++) {
      draw[t] = VGEO_INVALID;
      if (child[t] == VGEO_INVALID) continue;
      draw[t] = cutClusterByError(inst[t], child[t], cluster[t]);
      if (draw[t] != VGEO_INVALID && clusterHidden(drawInstance[t], child[t], inst[t], cluster[t], cone[t])) draw[t] = VGEO_INVALID;
      if (draw[t] != VGEO_INVALID) drawn++;
    }
    uint index;
    SUBGROUP_ATOMIC_ADD(counters.drawCount, drawn, index);
    [[unroll]] for (uint t = 0u; t < kLaneTests; t++) {
      if (draw[t] != VGEO_INVALID) writeDraw(index++, drawInstance[t], draw[t]);
    }
  }
  noteLoops();
  barrier();
}

#ifdef VGEO_PROFILE
// Worker profile (layout in shaderio.h): lane 0 stamps each iteration with the device clock and records
// the iterations that took items; the others are only counted.
layout(set = 0, binding = VGEO_BINDING_WORKER_PROFILE, std430) buffer ProfileBuffer { uint profile[]; };
uvec2 pStart, pClaimed, pTaken, pBegin;
uint pIterations = 0u, pRecorded = 0u, pPolls = 0u, pPollTicks = 0u;
#define PROFILE_STAMP(t) if (gl_LocalInvocationIndex == 0u) t = clockRealtime2x32EXT()
void profileIteration(uint items, uint tests1, uint tests2, uint claimed) {  // lane 0, end of an iteration
  uvec2 end = clockRealtime2x32EXT();
  pIterations++;
  if (items == 0u) {
    pPolls++;
    pPollTicks += end.x - pStart.x;
  } else if (pRecorded < VGEO_PROFILE_ITERATIONS) {
    uint at = gl_WorkGroupID.x * VGEO_PROFILE_WORKER_WORDS + VGEO_PROFILE_HEADER_WORDS + pRecorded * VGEO_PROFILE_ITERATION_WORDS;
    uvec2 stamps[4] = uvec2[4](pStart, pClaimed, pTaken, end);
    for (uint i = 0u; i < 4u; i++) {
      profile[at + 2u * i] = stamps[i].x;
      profile[at + 2u * i + 1u] = stamps[i].y;
    }
    profile[at + 8u] = items;
    profile[at + 9u] = tests1;
    profile[at + 10u] = tests2;
    profile[at + 11u] = claimed;
    pRecorded++;
  }
}
void profileExit() {  // lane 0
  uvec2 exitTime = clockRealtime2x32EXT();
  uint at = gl_WorkGroupID.x * VGEO_PROFILE_WORKER_WORDS;
  profile[at] = pRecorded;
  profile[at + 1u] = pIterations;
  profile[at + 2u] = pPolls;
  profile[at + 3u] = pPollTicks;
  profile[at + 4u] = pBegin.x;
  profile[at + 5u] = pBegin.y;
  profile[at + 6u] = exitTime.x;
  profile[at + 7u] = exitTime.y;
}
#else
#define PROFILE_STAMP(t)
#endif

// Lane 0 sets the workgroup's shared state before its first claim.
void startWorker() {
  sHolding = 0u;
  sLoops = 0u;
  sRound = 0u;
  sClaiming = 0u;
  sDone = 0u;
  sDoneNodes = 0u;
  sEntryCounts[0] = 0u;
  sEntryCounts[1] = 0u;
  sKeepCount = 0u;
  sFinal = kMoreMayCome;
  sLetGo = 0u;
  sNoItems = 0u;
  // The first claim goes out at once (a load of queueWrite first put a round trip in front of every
  // frame's work), sized to take all of instance culling's items if the last frame's count holds (the
  // least batch when there is none); the watch lane sizes the next ones by the backlog. An empty queue
  // ends at the first claim (sNoItems).
  const uint expected = frame.firstClaimItems;
  sBatch = clamp((expected + gl_NumWorkGroups.x - 1u) / gl_NumWorkGroups.x, kMinBatch, uint(VGEO_TRAVERSAL_WORKGROUP));
}

// Small scenes (frame.cullInTraversal): worker w culls instances w, w + workers, ... first, their items
// written into slots that the other workers may have claimed already (they wait on them as on any slot
// past the frontier). The host counted every instance in nodesPending and each culling takes its own off,
// so no worker sees 0 before all are queued.
void cullInstancesFirst() {
  for (uint i = gl_WorkGroupID.x; i < passInstanceCount(); i += gl_NumWorkGroups.x) cullInstancesSpread(i, true);
}

// Claims this iteration's slots for the workgroup (sBase, sCount), or decides that it leaves (sExit,
// sNoItems). Uniform: every lane returns with the same shared values.
void claimSlots(uint lane, bool firstClaim) {
  // Beside the first claim: when instance culling queued nothing, nothing will ever be queued (only node
  // items produce items), and the workers leave without reading their slots.
  if (lane == kWatchLane && firstClaim && frame.claimMode == VGEO_CLAIM_PAST_FRONTIER && frame.cullInTraversal == 0u) sNoItems = counters.queueWrite == counters.queueBase ? 1u : 0u;
  if (lane == 0u) {
    sExit = kWorkerStays;
    sCount = 0u;
    if (sLetGo != 0u) {
      sExit = kWorkerDone;  // past the end: every item is claimed (see Termination)
    } else if (sHolding == 0u) {
      if (frame.iterationBudget != 0u && sLoops >= frame.iterationBudget) {
        sExit = kWorkerOutOfBudget;
      } else if (frame.claimMode == VGEO_CLAIM_PAST_FRONTIER) {
        sBase = atomicAdd(counters.queueRead, sBatch);  // one atomic on the chain of steps, nothing before it
        sCount = sBatch;
      } else {
        sRead = atomicOr(counters.queueRead, 0u);
        sReserved = min(atomicOr(counters.queueWrite, 0u), frame.queueCapacity);
        sWritten = VGEO_TRAVERSAL_WORKGROUP;
        sClaiming = 1u;
      }
    }
  }
  barrier();
  if (sClaiming != 0u) {
    // Claim mode 1: only the written prefix of the slots after the read position, found by all lanes
    // at once, is claimed, so no lane ever waits on a slot (on lavapipe a wait on a reserved slot can
    // outlast every worker's iteration budget).
    uint s = sRead + lane;
    if (s >= sReserved || !slotWritten(s)) atomicMin(sWritten, lane);
    barrier();
    if (lane == 0u) {
      sClaiming = 0u;
      if (sWritten > 0u && atomicCompSwap(counters.queueRead, sRead, sRead + sWritten) == sRead) {
        sBase = sRead;
        sCount = sWritten;
      } else if (sRead >= sReserved && atomicOr(counters.nodesPending, 0u) == 0u) {
        sExit = kWorkerDone;  // all claimed, and nothing more will be written (see Termination)
      }
    }
    barrier();
  }
}

// The worker leaves (lane 0): the profile, the budget count, and the draw arguments if it is the last.
void leaveWorker() {
#ifdef VGEO_PROFILE
  profileExit();
#endif
  if (sExit == kWorkerOutOfBudget) atomicAdd(counters.budgetExits, 1u);
  // The last worker to leave writes the draw arguments: every other worker's draw-list atomics
  // returned before its own exit count (a barrier of its workgroup lies between), so the count it
  // reads is final. Saves the dispatch of finalize.comp and its barrier (draw_arguments.glsl).
  memoryBarrierBuffer();
  if (atomicAdd(counters.workgroupsExited, 1u) == gl_NumWorkGroups.x - 1u) {
    memoryBarrierBuffer();
    writeDrawArguments();
  }
}

// Each lane reads its slot (holding it, in claim mode 0, until a producer fills it) and takes its item:
// node and group items become this iteration's round entries (traverse_common.glsl). Ends with the
// workgroup's view of whether anything more will be written (sFinal, sLetGo).
void takeSlots(uint lane, inout uint slot) {
  if (lane < sCount) slot = sBase + lane;
  uint instance, code;
  bool have = false;
  if (frame.claimMode == VGEO_CLAIM_WRITTEN) {
    // Claimed slots are written (above).
    have = slot != VGEO_INVALID && takeQueue(slot, instance, code);
    slot = VGEO_INVALID;
  } else {
    if (lane == kWatchLane) {
      // Beside the lanes' slot reads (a lane of another subgroup than the first slots' on NVIDIA).
      uint pending = counters.nodesPending, written = counters.queueWrite, read = counters.queueRead;
      sFinal = pending != 0u ? kMoreMayCome : read >= written ? kAllClaimed : kNoMoreWritten;
      sBatch = clamp((written > read ? written - read : 0u) / gl_NumWorkGroups.x, kMinBatch, uint(VGEO_TRAVERSAL_WORKGROUP));
    }
    if (slot != VGEO_INVALID && slot < frame.queueCapacity && takeQueue(slot, instance, code)) {
      have = true;
      slot = VGEO_INVALID;
    }
  }
  bool node = false;
  if (have) node = sCount >= kSerialBatch ? takeItemSerial(instance, code) : takeItem(instance, code);
  uint taken = subgroupAdd(have ? 1u : 0u), takenNodes = subgroupAdd(node ? 1u : 0u);
  if (subgroupElect() && taken != 0u) atomicAdd(sDone, taken);
  if (subgroupElect() && takenNodes != 0u) atomicAdd(sDoneNodes, takenNodes);
  if (lane == 0u) sHolding = 0u;
  noteLoops();
  barrier();
  // No node item pending when the slots were read: a slot still unfilled never will be.
  if (sFinal != kMoreMayCome && slot != VGEO_INVALID) {
    slot = VGEO_INVALID;
    sLetGo = 1u;
  }
  if (lane == 0u && sFinal == kAllClaimed) sLetGo = 1u;  // nothing left to claim: leave after these items
}

// Tests the entries of both rounds: round 1 the children of the items taken, round 2 the clusters of the
// groups round 1 kept (queued or tested here, queueKept).
void runRounds(uint lane) {
  // The items count as done below, after both rounds: every child node they keep is reserved by then.
  // Uniform: shared, read after a barrier. A round of cluster entries only (round 1: no node item taken;
  // round 2 always) with more tests than lanes preloads them, in claims below kSerialBatch on GPUs
  // (lavapipe runs a test a lane: kLaneTests is 1 there; bench/README.md, cut selection).
  const uint testMask = (1u << kTestBits) - 1u;
  const bool preload = frame.claimMode == VGEO_CLAIM_PAST_FRONTIER && sCount < kSerialBatch;
  if (preload && sDoneNodes == 0u && (sEntryCounts[0] & testMask) > VGEO_TRAVERSAL_WORKGROUP) runClusterRound(0u, lane);
  else if (sEntryCounts[0] != 0u) runRound(0u, lane);
  if (sKeepCount != 0u) {
    queueKept(lane);
    noteLoops();
    barrier();
  }
  if (preload && (sEntryCounts[1] & testMask) > VGEO_TRAVERSAL_WORKGROUP) runClusterRound(1u, lane);
  else if (sEntryCounts[1] != 0u) runRound(1u, lane);
}

// Lane 0 closes the iteration: counts the lanes still holding slots and lavapipe's loop iterations, and
// takes this iteration's items off the counters.
void endIteration(uint lane, uint slot) {
  uint holding = subgroupAdd(slot != VGEO_INVALID ? 1u : 0u);
  if (subgroupElect() && holding != 0u) atomicAdd(sHolding, holding);
  // lavapipe counts a loop iteration for a whole SIMD vector of lanes whenever any of them iterates,
  // over every loop inside the outermost one: bound that by this iteration and the most inner
  // iterations any lane ran, plus, as a margin, one count per barrier (up to 10) and vector of 8 lanes.
  if (lane == 0u) {
    sLoops += 1u + sRound + 10u * (VGEO_TRAVERSAL_WORKGROUP / 8u);
    sRound = 0u;
#ifdef VGEO_PROFILE
    const uint testMask = (1u << kTestBits) - 1u;
    profileIteration(sDone, sEntryCounts[0] & testMask, sEntryCounts[1] & testMask, sCount);
#endif
    // After the barrier: every child these items produced was reserved (and added to nodesPending)
    // before they are taken off.
    if (sDoneNodes != 0u) atomicAdd(counters.nodesPending, 0u - sDoneNodes);
    if (sDone != 0u) atomicAdd(counters.itemsDone, sDone);
    sDone = 0u;
    sDoneNodes = 0u;
    sEntryCounts[0] = 0u;
    sEntryCounts[1] = 0u;
    sKeepCount = 0u;
  }
}

void main() {
  beginStats();
  const uint lane = gl_LocalInvocationIndex;
  uint slot = VGEO_INVALID;  // the slot this lane holds (claim mode 0)
  bool firstClaim = true;
  PROFILE_STAMP(pBegin);
  if (lane == 0u) startWorker();
  if (frame.cullInTraversal != 0u) cullInstancesFirst();
  for (;;) {
    barrier();
    PROFILE_STAMP(pStart);
    claimSlots(lane, firstClaim);
    firstClaim = false;
    PROFILE_STAMP(pClaimed);
    if (sExit != kWorkerStays || sNoItems != 0u) {  // uniform: both are shared
      if (lane == 0u) leaveWorker();
      break;
    }
    gLoops = 0u;
    takeSlots(lane, slot);
    PROFILE_STAMP(pTaken);
    runRounds(lane);
    endIteration(lane, slot);
  }
  flushStats();
}
