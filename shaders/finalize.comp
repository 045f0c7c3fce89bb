#version 450
// finalize.comp: one thread, after the traversal. Sizes the next step by the draw list (never more
// than it holds): the triangle-culling dispatch, one workgroup an entry in rows of 65,535 (the least
// maxComputeWorkGroupCount a device may have), or, without triangle culling, the indirect draw of
// 384 vertices an entry.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 1) in;
#include "common.glsl"

void main() {
  uint listed = min(counters.drawCount, frame.drawCapacity);
  counters.dispatch[0] = min(listed, 65535u);
  counters.dispatch[1] = (listed + 65534u) / 65535u;
  counters.dispatch[2] = 1u;
  counters.draw[0] = 3u * VGEO_MAX_CLUSTER_TRIANGLES;
  counters.draw[1] = frame.triangleCull != 0u ? 0u : listed;
  counters.draw[2] = 0u;
  counters.draw[3] = 0u;
  counters.queueHighWater = counters.queueWrite;  // the queue is never reused within a frame
}
