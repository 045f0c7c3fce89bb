#version 450
// traverse_persistent.comp: persistent-thread traversal (DESIGN.md, "Persistent threads without
// deadlock"). A fixed set of workgroups drains one global queue until it is empty and no item is in
// flight. Control flow around the queue is uniform: lane 0 claims for the workgroup and broadcasts
// through shared memory; no lane ever spins on a flag another lane of its workgroup must set.
//
// Claiming (frame.claimMode):
//   0  past the frontier (GPUs): one atomicAdd claims 64 slots, produced or not; each lane keeps its slot
//      until a producer fills it. One atomic a batch scaled to 16k workgroups on an H100 (GPU-NOTES 9).
//   1  reserved items only (lavapipe): compare-and-swap over slots already reserved, whose producers are
//      running and fill them at once; a workgroup holds nothing between iterations, so it can leave on
//      the iteration budget (lavapipe ends loops silently after 65,535 iterations, GPU-NOTES 1).
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

bool quiescent() {
  uint done = atomicOr(counters.itemsDone, 0u);
  memoryBarrierBuffer();
  uint written = atomicOr(counters.queueWrite, 0u);
  return done == written;
}

void main() {
  const uint lane = gl_LocalInvocationIndex;
  uint slot = VGEO_INVALID;  // the slot this lane holds (claim mode 0)
  uint iterations = 0u;
  if (lane == 0u) sHolding = 0u;
  for (;;) {
    barrier();
    if (lane == 0u) {
      sExit = 0u;
      sCount = 0u;
      if (sHolding == 0u) {
        if (frame.iterationBudget != 0u && iterations >= frame.iterationBudget) {
          sExit = 2u;
        } else if (frame.claimMode == 0u) {
          if (quiescent()) sExit = 1u;
          else {
            sBase = atomicAdd(counters.queueRead, VGEO_TRAVERSAL_WORKGROUP);
            sCount = VGEO_TRAVERSAL_WORKGROUP;
          }
        } else {
          uint read = atomicOr(counters.queueRead, 0u);
          uint reserved = min(atomicOr(counters.queueWrite, 0u), frame.queueCapacity);
          if (read < reserved) {
            uint want = min(uint(VGEO_TRAVERSAL_WORKGROUP), reserved - read);
            if (atomicCompSwap(counters.queueRead, read, read + want) == read) {
              sBase = read;
              sCount = want;
            }
          } else if (quiescent()) {
            sExit = 1u;
          }
        }
      }
    }
    barrier();
    if (sExit != 0u) {
      if (lane == 0u) {
        atomicAdd(counters.workgroupsExited, 1u);
        if (sExit == 2u) atomicAdd(counters.budgetExits, 1u);
      }
      break;
    }
    iterations++;
    if (lane < sCount) slot = sBase + lane;

    uint instance, code;
    if (frame.claimMode == 1u) {
      // Reserved slots are being written by running producers: wait for this one, then process it.
      if (slot != VGEO_INVALID) {
        while (!takeQueue(slot, instance, code)) {}
        processItem(instance, code);
        atomicAdd(counters.itemsDone, 1u);
        slot = VGEO_INVALID;
      }
    } else if (slot != VGEO_INVALID) {
      if (slot < frame.queueCapacity && takeQueue(slot, instance, code)) {
        processItem(instance, code);
        atomicAdd(counters.itemsDone, 1u);
        slot = VGEO_INVALID;
      } else if (quiescent()) {
        slot = VGEO_INVALID;  // will never be filled
      }
    }
    if (lane == 0u) sHolding = 0u;
    barrier();
    if (slot != VGEO_INVALID) atomicAdd(sHolding, 1u);
  }
}
