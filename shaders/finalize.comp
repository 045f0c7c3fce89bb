#version 450
// finalize.comp: one thread; the indirect draw of the listed clusters (never more than the list holds).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 1) in;
#include "common.glsl"

void main() {
  counters.draw[0] = 3u * VGEO_MAX_CLUSTER_TRIANGLES;
  counters.draw[1] = min(counters.drawCount, frame.drawCapacity);
  counters.draw[2] = 0u;
  counters.draw[3] = 0u;
  counters.queueHighWater = counters.queueWrite;  // the queue is never reused within a frame
}
