#version 450
// draw_visibility.frag: a fragment of the hardware's draws (draw.vert: listed triangles; patch_grid.vert:
// patch grids) in frames whose render pass has no attachments: it takes its place in the visibility
// buffer as the compute rasterizers' samples do, a 64-bit atomicMax of (depth, id), so that one resolve
// (resolve.comp) shades every pixel; in --mode overdraw it counts. Fragments are not depth-tested (there is no depth buffer): the
// atomic keeps the nearest.
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "visibility.glsl"

layout(location = 5) flat in uvec2 inId;  // visibility id, low word first

void main() {
  uint pixel = uint(gl_FragCoord.y) * uint(frame.viewportWidth) + uint(gl_FragCoord.x);
  if (frame.mode == VGEO_MODE_OVERDRAW) {
    atomicAdd(overdraw[pixel], 1u);
  } else {
    atomicMax(visibility[pixel], visibilityWord(gl_FragCoord.z, uint64_t(inId.y) << 32 | uint64_t(inId.x)));
  }
}
