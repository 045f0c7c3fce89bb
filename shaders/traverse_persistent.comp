#version 450
// traverse_persistent.comp: persistent-thread traversal (DESIGN.md, "Persistent threads without
// deadlock"). A fixed set of workgroups drains one global queue until it is empty and no item is in
// flight. Control flow around the queue is uniform: lane 0 claims for the workgroup and broadcasts
// through shared memory; no lane ever spins on a flag another lane of its workgroup must set.
//
// Claiming (frame.claimMode):
//   0  past the frontier (GPUs): one atomicAdd claims 64 slots, produced or not; each lane keeps its slot
//      until a producer fills it. One atomic a batch scaled to 16k workgroups on an H100 (GPU-NOTES 9).
//   1  written items only (lavapipe): the lanes find the written prefix after the read position and
//      lane 0 claims it by compare-and-swap; nobody waits on a slot, a workgroup holds nothing between
//      iterations, so it can leave on
//      the iteration budget (lavapipe ends loops silently after 65,535 iterations per invocation, all
//      loops counted, GPU-NOTES 1: every loop of the traversal counts into gLoops).
// Termination: itemsDone == queueWrite (read in that order) means nothing is in flight and nothing can
// be produced any more; overflowed items count as done.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
layout(local_size_x = VGEO_TRAVERSAL_WORKGROUP) in;
#include "traverse_common.glsl"

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
// Group items of many clusters are tested by the whole workgroup, not by their lane (a leaf-level
// group holds up to ~32 clusters; one lane testing them in a row was the long pole of close views).
// They become entries; cluster k of the iteration is cluster k - sEntryStart[e] of entry e.
// (Spreading a node's children over the lanes too, in iterations with few items, lost items on
// lavapipe; not pursued.)
shared uint sEntries, sClusters;
shared uint sEntryInstance[VGEO_TRAVERSAL_WORKGROUP], sEntryFirst[VGEO_TRAVERSAL_WORKGROUP];
shared uint sEntryStart[VGEO_TRAVERSAL_WORKGROUP + 1];

// Groups of more clusters than this are shared; smaller ones (the roots of far instances) are tested by
// their lane. Measured on an H100: sharing every group made close views 30% faster and far views of
// 100,000 instances 80% slower.
const uint kSharedGroupClusters = 8u;

void takeItem(uint instance, uint code) {
  if ((code & VGEO_ITEM_GROUP_BIT) != 0u) {
    Group g = groups[code & ~VGEO_ITEM_GROUP_BIT];
    if (g.clusterCount > kSharedGroupClusters) {
      gNodes++;
      uint e = atomicAdd(sEntries, 1u);
      sEntryInstance[e] = instance;
      sEntryFirst[e] = g.clusterOffset;
      sEntryStart[e + 1u] = g.clusterCount;  // a count until lane 0 sums them
      return;
    }
  }
  processItem(instance, code);
}

// Every lane calls it after a barrier, and only when sEntries != 0 (barriers): the entries' clusters,
// spread over the lanes.
void testEntries(uint lane) {
  if (lane == 0u) {
    sEntryStart[0] = 0u;
    for (uint e = 0u; e < sEntries; e++) {
      gLoops++;
      sEntryStart[e + 1u] += sEntryStart[e];
    }
    sClusters = sEntryStart[sEntries];
  }
  barrier();
  for (uint k = lane; k < sClusters; k += VGEO_TRAVERSAL_WORKGROUP) {
    gLoops++;
    uint lo = 0u, hi = sEntries - 1u;  // the last entry starting at or before k
    while (lo < hi) {
      gLoops++;
      uint mid = (lo + hi + 1u) / 2u;
      if (sEntryStart[mid] <= k) lo = mid;
      else hi = mid - 1u;
    }
    testCluster(sEntryInstance[lo], sEntryFirst[lo] + k - sEntryStart[lo]);
  }
  atomicMax(sRound, gLoops);
  barrier();
}

bool quiescent() {
  uint done = atomicOr(counters.itemsDone, 0u);
  memoryBarrierBuffer();
  uint written = atomicOr(counters.queueWrite, 0u);
  return done == written;
}

void main() {
  beginStats();
  const uint lane = gl_LocalInvocationIndex;
  uint slot = VGEO_INVALID;  // the slot this lane holds (claim mode 0)
  if (lane == 0u) {
    sHolding = 0u;
    sLoops = 0u;
    sRound = 0u;
    sClaiming = 0u;
    sDone = 0u;
    sEntries = 0u;
    sPolls = 0u;
  }
  for (;;) {
    barrier();
    if (lane == 0u) {
      sExit = 0u;
      sCount = 0u;
      // Held slots that will never be filled are let go once nothing is in flight; checked every 4th
      // iteration only (two global atomics on the chain of dependent steps a traversal waits through).
      sPolls = sHolding != 0u ? sPolls + 1u : 0u;
      sQuiet = sHolding != 0u && (sPolls & 3u) == 0u && quiescent() ? 1u : 0u;
      if (sHolding == 0u) {
        if (frame.iterationBudget != 0u && sLoops >= frame.iterationBudget) {
          sExit = 2u;
        } else if (frame.claimMode == 0u) {
          if (quiescent()) sExit = 1u;
          else {
            sBase = atomicAdd(counters.queueRead, VGEO_TRAVERSAL_WORKGROUP);
            sCount = VGEO_TRAVERSAL_WORKGROUP;
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
      if (s >= sReserved || atomicOr(queue[2 * s], 0u) == VGEO_INVALID) atomicMin(sWritten, lane);
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
    if (sExit != 0u) {
      if (lane == 0u) {
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
      takeItem(instance, code);
      atomicAdd(sDone, 1u);
    }
    if (lane == 0u) sHolding = 0u;
    atomicMax(sRound, gLoops);
    barrier();
    // Shared groups count as done with the iteration's other items, below: they make no queue items, and
    // this workgroup tests their clusters before it can claim or leave again.
    if (sEntries != 0u) testEntries(lane);  // uniform: shared, read after the barrier
    if (slot != VGEO_INVALID) atomicAdd(sHolding, 1u);
    // lavapipe counts a loop iteration for a whole SIMD vector of lanes whenever any of them iterates,
    // over every loop inside the outermost one: bound that by this iteration and the most inner
    // iterations any lane ran, plus, as a margin, one count per barrier and vector of 8 lanes.
    if (lane == 0u) {
      sLoops += 1u + sRound + 5u * (VGEO_TRAVERSAL_WORKGROUP / 8u);
      sRound = 0u;
      // After the barrier: every child these items produced was reserved before they count as done.
      if (sDone != 0u) atomicAdd(counters.itemsDone, sDone);
      sDone = 0u;
      sEntries = 0u;
    }
  }
  flushStats();
}
