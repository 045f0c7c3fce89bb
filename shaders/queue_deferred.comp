#version 450
// queue_deferred.comp: queue_deferred.glsl in a dispatch of its own, 64 deferred items a workgroup, for the
// frames whose persistent traversal culls the instances itself (no instance-culling dispatch to run it).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
layout(local_size_x = 64) in;
#include "traverse_common.glsl"
#include "queue_deferred.glsl"

void main() { queueDeferredItems(gl_WorkGroupID.x, 64u); }
