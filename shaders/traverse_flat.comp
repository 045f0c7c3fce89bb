#version 450
// traverse_flat.comp: one thread per (visible instance, cluster), no hierarchy: the baseline the
// hierarchical traversals are measured against. The visible instances are the first queue items
// of the pass (cull_instances.comp, from counters.queueBase); y and z of the dispatch index them.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
layout(local_size_x = VGEO_TRAVERSAL_WORKGROUP) in;
#include "traverse_common.glsl"

void main() {
  beginStats();
  uint visible = gl_WorkGroupID.y + gl_WorkGroupID.z * 65535u;
  if (visible < counters.visibleInstances) {
    uint instance = queue[2 * (counters.queueBase + visible)];
    Geometry g = geometries[instances[instance].geometry];
    uint i = gl_GlobalInvocationID.x;
    if (i < g.clusterCount) testCluster(instance, g.clusterOffset + i);
  }
  flushStats();
}
