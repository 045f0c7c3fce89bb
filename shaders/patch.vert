#version 450
// patch.vert: each vertex of the tessellated draw is one listed patch; it hands its index in the patch
// list to patch.tesc. The draw is instances of frame.patchesPerInstance patches: lavapipe runs each
// instance through its tessellator on its own, whose output of one run must stay under 65,536 vertices
// (16-bit indices; past that, triangles joined unrelated vertices), and it restarts gl_PrimitiveID
// between the batches it splits a draw into, so the index is made here, right on every device.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
layout(location = 0) out uint vPatch;
void main() { vPatch = uint(gl_InstanceIndex) * frame.patchesPerInstance + uint(gl_VertexIndex); }
