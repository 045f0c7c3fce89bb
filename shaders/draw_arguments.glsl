// draw_arguments.glsl: once the draw list is final, sizes the next step by it (never more than it
// holds): the triangle-culling dispatch, one workgroup an entry (cull_triangles.comp) or
// VGEO_PACKED_CULL_ENTRIES (cull_small_clusters.comp), in rows of 65,535 (the least
// maxComputeWorkGroupCount a device may have), or, without triangle culling, the indirect draw of 384
// vertices an entry. One invocation calls it: finalize.comp (levels), the flat traversal's reset pass,
// or the persistent traversal's last worker to leave, so the last two need no dispatch of its own.
// With occlusion culling the late pass's entries follow the early pass's (counters.drawBase on).
void writeDrawArguments() {
  uint total = min(atomicOr(counters.drawCount, 0u), frame.drawCapacity), listed = total - counters.drawBase;
  // Clusters of few triangles on average (far instances' roots) share workgroups where that pays.
  bool packed = listed > 0u && atomicOr(counters.triangles, 0u) / total < frame.packedCullBelow;
  uint packedWorkgroups = packed ? (listed + VGEO_PACKED_CULL_ENTRIES - 1u) / VGEO_PACKED_CULL_ENTRIES : 0u;
  uint workgroups = packed ? 0u : listed;
  counters.dispatch[0] = min(workgroups, 65535u);
  counters.dispatch[1] = (workgroups + 65534u) / 65535u;
  counters.dispatch[2] = 1u;
  counters.packedCullDispatch[0] = min(packedWorkgroups, 65535u);
  counters.packedCullDispatch[1] = (packedWorkgroups + 65534u) / 65535u;
  counters.packedCullDispatch[2] = 1u;
  counters.draw[0] = 3u * VGEO_MAX_CLUSTER_TRIANGLES;
  counters.draw[1] = frame.triangleCull != 0u ? 0u : listed;
  counters.draw[2] = 0u;
  counters.draw[3] = counters.drawBase;  // first instance: draw.vert's instance i is entry i
  counters.queueHighWater = atomicOr(counters.queueWrite, 0u);  // the queue is never reused within a frame
}
