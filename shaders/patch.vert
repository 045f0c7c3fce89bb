#version 450
// patch.vert: the tessellated draw's vertices carry nothing: each is one patch, which patch.tesc finds
// by gl_PrimitiveID in the patch list.
void main() {}
