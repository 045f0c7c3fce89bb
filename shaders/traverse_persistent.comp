#version 450
// traverse_persistent.comp: persistent-thread traversal (DESIGN.md, "Persistent threads without
// deadlock"). A fixed set of workgroups drains one global queue until it is empty and no item is in
// flight. Control flow around the queue is uniform: lane 0 claims for the workgroup and broadcasts
// through shared memory; no lane ever spins on a flag another lane of its workgroup must set.
//
// Claiming (frame.claimMode):
//   0  past the frontier (GPUs): one atomicAdd claims a batch of slots, produced or not; each lane keeps
//      its slot until a producer fills it. The batch follows the backlog: the items written and not yet
//      claimed shared over the workgroups, from kMinBatch (a chain of single items, as in a close view of
//      a few instances: spread over many workgroups) to 64 (100,000 instances: fewer claims).
//   1  written items only (lavapipe): the lanes find the written prefix after the read position and
//      lane 0 claims it by compare-and-swap; nobody waits on a slot, a workgroup holds nothing between
//      iterations, so it can leave on the iteration budget (lavapipe ends loops silently after 65,535
//      iterations per invocation, all loops counted, GPU-NOTES 1: every loop here counts into gLoops).
// Termination: itemsDone == queueWrite (read in that order) means nothing is in flight and nothing can
// be produced any more; overflowed items count as done.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#ifdef VGEO_PROFILE
#extension GL_EXT_shader_realtime_clock : require
#endif
#include "common.glsl"
layout(local_size_x = VGEO_TRAVERSAL_WORKGROUP) in;
#include "traverse_common.glsl"

const uint kMinBatch = 4u;         // measured on an H100: 4 to 8 best for close views, 16 and more worse
const uint kSerialBatch = 32u;     // batches this large are tested a lane an item (see takeItemSerial)

shared uint sBase;     // first slot of the batch claimed this iteration
shared uint sCount;    // slots claimed this iteration (0: none)
shared uint sExit;
shared uint sHolding;  // lanes still holding a slot (claim mode 0)
shared uint sLoops;    // loop iterations so far, as lavapipe counts them (see below)
shared uint sRound;    // the most inner-loop iterations any lane ran this iteration
shared uint sRead, sReserved, sWritten, sClaiming;  // claim mode 1
shared uint sDone;     // items this workgroup finished this iteration (added to itemsDone once)
shared uint sQuiet;    // claim mode 0: nothing is in flight any more (checked by lane 0 for all)
shared uint sPolls;    // claim mode 0: iterations in a row spent holding slots

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
  if (lane == 0u) sKeepFirst = reserveQueue(sKeepCount);
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

// A taken queue item becomes a round-1 entry.
void takeItem(uint instance, uint code) {
  gNodes++;
  if ((code & VGEO_ITEM_GROUP_BIT) != 0u) {
    Group g = groups[code & ~VGEO_ITEM_GROUP_BIT];
    addEntry(0u, instance, g.clusterOffset, g.clusterCount, kClusters);
  } else {
    BvhNode node = nodes[code];
    bool leaf = (node.childCountAndFlags & VGEO_NODE_LEAF_BIT) != 0u;
    addEntry(0u, instance, node.childOffset, node.childCountAndFlags & ~VGEO_NODE_LEAF_BIT, leaf ? kGroupChildren : kNodeChildren);
  }
}

// A child of an entry, whoever tests it. Returns the draw-list code of a cluster to draw, or VGEO_INVALID.
uint testChild(uint instance, uint child, uint kind) {
  if (kind == kClusters) {
    return cutCluster(instance, child);
  } else if (kind == kGroupChildren) {
    Group g = groups[child];
    if (mayHoldDrawn(instances[instance], g.sphere, g.error)) {
      gNodes++;
      addEntry(1u, instance, g.clusterOffset, g.clusterCount, kClusters);
    }
  } else if (childMayHoldDrawn(instances[instance], child, false)) {
    keepItem(instance, child);
  }
  return VGEO_INVALID;
}

// Appends (instance, draw) to the draw list for the calling lanes whose draw is not VGEO_INVALID, with one
// atomic a subgroup (one a cluster, on one counter, was measured to cost up to 0.1 ms at 100,000 instances).
void appendDraws(uint instance, uint draw) {
  uint index;
  SUBGROUP_ATOMIC_ADD(counters.drawCount, draw != VGEO_INVALID ? 1u : 0u, index);
  if (draw != VGEO_INVALID) writeDraw(index, instance, draw);
}

// A taken item whose children its own lane tests, for large batches (100,000 instances): spreading them
// costs more than it saves once every lane has an item (far views 3-5% slower on an H100).
void takeItemSerial(uint instance, uint code) {
  gNodes++;
  if ((code & VGEO_ITEM_GROUP_BIT) != 0u) {
    Group g = groups[code & ~VGEO_ITEM_GROUP_BIT];
    addEntry(1u, instance, g.clusterOffset, g.clusterCount, kClusters);
    return;
  }
  BvhNode node = nodes[code];
  uint count = node.childCountAndFlags & ~VGEO_NODE_LEAF_BIT;
  uint kind = (node.childCountAndFlags & VGEO_NODE_LEAF_BIT) != 0u ? kGroupChildren : kNodeChildren;
  for (uint i = 0u; i < count; i++) {
    gLoops++;
    testChild(instance, node.childOffset + i, kind);  // node or group children: nothing to draw
  }
}

// Every lane calls it after a barrier, with the round's entry count uniform and non-zero.
void runRound(uint round, uint lane) {
  const uint base = round == 0u ? 0u : kRound2;
  const uint entries = sEntryCounts[round] >> kTestBits;
  const uint tests = sEntryCounts[round] & ((1u << kTestBits) - 1u);
  for (uint k = lane; k < tests; k += VGEO_TRAVERSAL_WORKGROUP) {
    gLoops++;
    uint lo = base, hi = base + entries - 1u;  // the last entry starting at or before k
    while (lo < hi) {
      gLoops++;
      uint mid = (lo + hi + 1u) / 2u;
      if (sEntryStart[mid] <= k) lo = mid;
      else hi = mid - 1u;
    }
    uint instance = sEntryInstance[lo];
    appendDraws(instance, testChild(instance, sEntryFirst[lo] + k - sEntryStart[lo], sEntryKind[lo]));
  }
  noteLoops();
  barrier();
}

#ifdef VGEO_PROFILE
// Worker profile (layout in shaderio.h): lane 0 stamps each iteration with the device clock and records
// the iterations that took items; the others are only counted.
layout(set = 0, binding = 21, std430) buffer ProfileBuffer { uint profile[]; };
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

// Nothing in flight, nothing more can be produced. `written`: the items reserved so far.
bool quiescent(out uint written) {
  uint done = counters.itemsDone;  // coherent loads, in this order
  memoryBarrierBuffer();
  written = counters.queueWrite;
  return done == written;
}
bool quiescent() {
  uint written;
  return quiescent(written);
}

void main() {
  beginStats();
  const uint lane = gl_LocalInvocationIndex;
  uint slot = VGEO_INVALID;  // the slot this lane holds (claim mode 0)
  PROFILE_STAMP(pBegin);
  if (lane == 0u) {
    sHolding = 0u;
    sLoops = 0u;
    sRound = 0u;
    sClaiming = 0u;
    sDone = 0u;
    sEntryCounts[0] = 0u;
    sEntryCounts[1] = 0u;
    sKeepCount = 0u;
    sPolls = 0u;
  }
  for (;;) {
    barrier();
    PROFILE_STAMP(pStart);
    if (lane == 0u) {
      sExit = 0u;
      sCount = 0u;
      // Held slots that will never be filled are let go once nothing is in flight; checked every 4th
      // iteration only (global loads on the chain of dependent steps a traversal waits through).
      sPolls = sHolding != 0u ? sPolls + 1u : 0u;
      sQuiet = sHolding != 0u && (sPolls & 3u) == 0u && quiescent() ? 1u : 0u;
      if (sHolding == 0u) {
        if (frame.iterationBudget != 0u && sLoops >= frame.iterationBudget) {
          sExit = 2u;
        } else if (frame.claimMode == 0u) {
          uint written;
          if (quiescent(written)) {
            sExit = 1u;
          } else {
            uint read = counters.queueRead;
            uint backlog = written > read ? written - read : 0u;
            uint batch = clamp(backlog / gl_NumWorkGroups.x, kMinBatch, uint(VGEO_TRAVERSAL_WORKGROUP));
            sBase = atomicAdd(counters.queueRead, batch);
            sCount = batch;
          }
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
      // at once, is claimed, so no lane ever waits on a slot. (Waiting on reserved slots, the first
      // version, sometimes stalled on lavapipe until every worker ran out of iterations.)
      uint s = sRead + lane;
      if (s >= sReserved || !slotWritten(s)) atomicMin(sWritten, lane);
      barrier();
      if (lane == 0u) {
        sClaiming = 0u;
        if (sWritten > 0u && atomicCompSwap(counters.queueRead, sRead, sRead + sWritten) == sRead) {
          sBase = sRead;
          sCount = sWritten;
        } else if (sRead >= sReserved && quiescent()) {
          sExit = 1u;
        }
      }
      barrier();
    }
    PROFILE_STAMP(pClaimed);
    if (sExit != 0u) {
      if (lane == 0u) {
#ifdef VGEO_PROFILE
        profileExit();
#endif
        atomicAdd(counters.workgroupsExited, 1u);
        if (sExit == 2u) atomicAdd(counters.budgetExits, 1u);
      }
      break;  // uniform: sExit is shared
    }
    gLoops = 0u;

    if (lane < sCount) slot = sBase + lane;
    uint instance, code;
    bool have = false;
    if (frame.claimMode == 1u) {
      // Claimed slots are written (above).
      have = slot != VGEO_INVALID && takeQueue(slot, instance, code);
      slot = VGEO_INVALID;
    } else if (slot != VGEO_INVALID) {
      if (slot < frame.queueCapacity && takeQueue(slot, instance, code)) {
        have = true;
        slot = VGEO_INVALID;
      } else if (sQuiet != 0u) {
        slot = VGEO_INVALID;  // will never be filled
      }
    }
    if (have) {
      if (sCount >= kSerialBatch) takeItemSerial(instance, code);
      else takeItem(instance, code);
    }
    uint taken = subgroupAdd(have ? 1u : 0u);
    if (subgroupElect() && taken != 0u) atomicAdd(sDone, taken);
    if (lane == 0u) sHolding = 0u;
    noteLoops();
    barrier();
    PROFILE_STAMP(pTaken);
    // The items count as done below, after both rounds: every child node they keep is reserved by then.
    if (sEntryCounts[0] != 0u) runRound(0u, lane);  // uniform: shared, read after a barrier
    if (sKeepCount != 0u) {
      queueKept(lane);
      noteLoops();
      barrier();
    }
    if (sEntryCounts[1] != 0u) runRound(1u, lane);
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
      // After the barrier: every child these items produced was reserved before they count as done.
      if (sDone != 0u) atomicAdd(counters.itemsDone, sDone);
      sDone = 0u;
      sEntryCounts[0] = 0u;
      sEntryCounts[1] = 0u;
      sKeepCount = 0u;
    }
  }
  flushStats();
}
