#version 450
// draw.frag: a fragment of the hardware draws (draw.vert, patch.tese) in the view of --mode (shade.glsl).
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "shade.glsl"

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec3 inBarycentric;
layout(location = 2) flat in uvec4 inIds;
layout(location = 3) flat in vec2 inInfo;
layout(location = 4) flat in uint inTriangle;
layout(location = 0) out vec4 outColor;

void main() {
  vec3 n = normalize(inNormal);
  if (!gl_FrontFacing) n = -n;
  float edge = 0.0;
  if (frame.mode == VGEO_MODE_WIRE) {
    vec3 d = fwidth(inBarycentric);
    vec3 a = smoothstep(vec3(0.0), d * 1.2, inBarycentric);
    edge = 1.0 - min(min(a.x, a.y), a.z);
  }
  outColor = targetColor(shadeSurface(n, inIds, inTriangle, inInfo, edge));
}
