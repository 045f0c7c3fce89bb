#version 450
// begin_late_pass.comp: one thread, between the two passes of a frame with occlusion culling. The late
// pass appends to the early pass's draw list (from counters.drawBase) and to its queue (from
// counters.queueBase: past every slot the early pass reserved or claimed, so none it left unwritten is
// reused; those between count as done), where queue_deferred.comp puts the items the early pass deferred
// first (its dispatch in counters.dispatch). Its triangle lists start afresh, the early pass's triangles
// being drawn already (their counts are summed), and what the traversals count a pass (visible instances,
// workers that left, pending nodes) starts again, the early pass's kept for the host.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 1) in;
#include "common.glsl"

void main() {
  counters.drawBase = min(counters.drawCount, frame.drawCapacity);
  const uint base = max(counters.queueWrite, counters.queueRead);
  counters.itemsDone += base - counters.queueWrite;
  counters.queueWrite = base;
  counters.queueRead = base;
  counters.queueBase = base;
  counters.levelStart = base;
  counters.levelEnd = base;
  // The deferred instances: culled by the traversal's workers (each pending until culled), or by
  // cull_instances.comp over just them.
  counters.nodesPending = frame.cullInTraversal != 0u ? counters.deferredInstances : 0u;
  const uint cullWorkgroups = (counters.deferredInstances + frame.cullInstancesPerWorkgroup - 1u) / frame.cullInstancesPerWorkgroup;
  counters.lateCullDispatch[0] = cullWorkgroups;  // along x, as the early pass's
  counters.lateCullDispatch[1] = 1u;
  counters.lateCullDispatch[2] = 1u;
  // With nothing deferred the persistent traversal does not run, and its last worker does not size the
  // late triangle culling: nothing to cull (the draw arguments follow from it, finalize_triangles.comp).
  const bool work = counters.deferredInstances + counters.deferredItems != 0u;
  counters.lateTraversalDispatch[0] = work ? frame.persistentWorkgroups : 0u;
  counters.lateTraversalDispatch[1] = 1u;
  counters.lateTraversalDispatch[2] = 1u;
  counters.packedCullDispatch[0] = 0u;
  counters.draw[1] = 0u;
  counters.earlyVisibleInstances = counters.visibleInstances;
  counters.visibleInstances = 0u;
  counters.earlySoftwareTriangles = counters.softwareTriangles;
  counters.softwareTriangles = 0u;
  counters.hardwareTriangles = 0u;
  counters.earlyBudgetExits = counters.budgetExits;
  counters.budgetExits = 0u;
  counters.workgroupsExited = 0u;
  const uint deferred = min(counters.deferredItems, frame.queueCapacity);
  counters.dispatch[0] = (deferred + 63u) / 64u;  // 0 when nothing was deferred: triangle culling's too
  counters.dispatch[1] = 1u;
  counters.dispatch[2] = 1u;
}
