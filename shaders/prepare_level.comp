#version 450
// prepare_level.comp: one thread. The next window is what was produced since the last one; writes the
// indirect dispatch for it.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 1) in;
#include "common.glsl"

void main() {
  counters.levelStart = counters.levelEnd;
  counters.levelEnd = min(counters.queueWrite, frame.queueCapacity);
  uint items = counters.levelEnd - counters.levelStart;
  counters.dispatch[0] = (items + VGEO_TRAVERSAL_WORKGROUP - 1u) / VGEO_TRAVERSAL_WORKGROUP;
  counters.dispatch[1] = 1u;
  counters.dispatch[2] = 1u;
}
