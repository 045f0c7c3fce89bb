#version 450
// finalize.comp: one thread, after the per-level traversal: the draw arguments (draw_arguments.glsl).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 1) in;
#include "common.glsl"
#include "draw_arguments.glsl"

void main() { writeDrawArguments(); }
