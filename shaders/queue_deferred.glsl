// queue_deferred.glsl: the late pass's first items, the queue items the early pass deferred
// (occlusion.glsl), queued as they are, a workgroup of `lanes` lanes taking `lanes` of them with one
// reservation, and their node items counted pending before the traversal starts (its termination,
// traverse_persistent.comp). Run by the late pass's instance culling (cull_instances.comp) in the same
// dispatch, or where the persistent traversal culls the instances itself by queue_deferred.comp.

shared uint sDeferredFirst, sDeferredNodes;

// Deferred items [workgroup * lanes, + lanes), by the whole workgroup (it has barriers).
void queueDeferredItems(uint workgroup, uint lanes) {
  const uint deferred = min(counters.deferredItems, frame.queueCapacity), first = workgroup * lanes;
  if (first >= deferred) return;  // the whole workgroup
  const uint lane = gl_LocalInvocationIndex, count = min(lanes, deferred - first);
  if (lane == 0u) {
    sDeferredFirst = reserveQueue(count);
    sDeferredNodes = 0u;
  }
  barrier();
  if (lane < count) {
    const uint instance = deferredItems[2u * (first + lane)], code = deferredItems[2u * (first + lane) + 1u];
    const bool node = (code & (VGEO_ITEM_GROUP_BIT | VGEO_ITEM_RUN_BIT)) == 0u;
    if (writeQueue(sDeferredFirst + lane, instance, code) && node) atomicAdd(sDeferredNodes, 1u);
  }
  barrier();
  if (lane == 0u && sDeferredNodes != 0u) atomicAdd(counters.nodesPending, sDeferredNodes);
}
