#version 450
// begin_late_pass.comp: begin_late_pass.glsl in a dispatch of its own, for the frames that build no depth
// pyramid (a frozen cut tests against the one it froze with).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 1) in;
#include "common.glsl"
#include "begin_late_pass.glsl"

void main() { beginLatePass(); }
