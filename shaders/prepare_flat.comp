#version 450
// prepare_flat.comp: one thread; the flat traversal's indirect dispatch over (clusters, instances).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 1) in;
#include "common.glsl"

void main() {
  uint visible = counters.visibleInstances;
  counters.dispatch[0] = visible == 0u ? 0u : (frame.maxClusters + VGEO_TRAVERSAL_WORKGROUP - 1u) / VGEO_TRAVERSAL_WORKGROUP;
  counters.dispatch[1] = min(visible, 65535u);
  counters.dispatch[2] = (visible + 65534u) / 65535u;
}
