#version 450
// patch.vert: each vertex of the tessellated draw is one listed patch; it hands its index in the patch
// list to patch.tesc. gl_PrimitiveID in the control shader would name the same patch on paper, but
// lavapipe restarts it between the batches it splits a large draw into (thousands of patches), so
// patches were drawn twice or not at all; the vertex index is right on every device.
layout(location = 0) out uint vPatch;
void main() { vPatch = uint(gl_VertexIndex); }
