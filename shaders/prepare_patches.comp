#version 450
// prepare_patches.comp: one thread, after triangle culling: the dispatch of cull_patches.comp, a
// workgroup a patch-drawn cluster of the patch-entry list.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 1) in;
#include "common.glsl"

void main() {
  uint workgroups = counters.patchEntries;
  counters.patchCullDispatch[0] = min(workgroups, 65535u);
  counters.patchCullDispatch[1] = (workgroups + 65534u) / 65535u;
  counters.patchCullDispatch[2] = 1u;
  counters.patchCullDispatch[3] = 0u;
}
