// begin_late_pass.glsl: one thread's work between the two passes of a frame with occlusion culling, at
// the end of the depth pyramid's build (build_depth_pyramid.comp) or, where the pyramid is kept (a frozen
// cut), in begin_late_pass.comp. The late pass appends to the early pass's draw list (from
// counters.drawBase) and to its queue (from counters.queueBase: past every slot the early pass reserved or
// claimed, so none it left unwritten is reused; those between count as done), where queue_deferred.glsl
// puts the items the early pass deferred first. Its triangle lists start afresh, the early pass's
// triangles being drawn already (their counts are summed), and what the traversals count a pass (visible
// instances, workers that left, pending nodes) starts again, the early pass's kept for the host.

void beginLatePass() {
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
  // Its workgroups also queue the deferred items (queue_deferred.glsl), as many a workgroup as it has lanes
  // (cull_instances.comp's variants: one lane an instance, or VGEO_CULL_SPREAD_WORKGROUP lanes).
  const uint deferred = min(counters.deferredItems, frame.queueCapacity);
  const uint cullLanes =
      frame.cullInstancesPerWorkgroup == VGEO_CULL_SERIAL_WORKGROUP ? VGEO_CULL_SERIAL_WORKGROUP : VGEO_CULL_SPREAD_WORKGROUP;
  const uint cullWorkgroups = (counters.deferredInstances + frame.cullInstancesPerWorkgroup - 1u) / frame.cullInstancesPerWorkgroup;
  counters.lateCullDispatch[0] = max(cullWorkgroups, (deferred + cullLanes - 1u) / cullLanes);  // along x, as the early pass's
  counters.lateCullDispatch[1] = 1u;
  counters.lateCullDispatch[2] = 1u;
  // With nothing deferred the persistent traversal does not run, and its last worker does not size the
  // late triangle culling: nothing to cull (the draw arguments follow from it, finalize_triangles.comp).
  const bool work = counters.deferredInstances + counters.deferredItems != 0u;
  counters.lateTraversalDispatch[0] = work ? frame.persistentWorkgroups : 0u;
  counters.lateTraversalDispatch[1] = 1u;
  counters.lateTraversalDispatch[2] = 1u;
  counters.earlyPackedCull = counters.packedCullDispatch[0];
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
  counters.dispatch[0] = (deferred + 63u) / 64u;  // queue_deferred.comp's; 0 when nothing was deferred: triangle culling's too
  counters.dispatch[1] = 1u;
  counters.dispatch[2] = 1u;
}
