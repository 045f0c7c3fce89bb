// visibility.glsl: the visibility buffer and the overdraw counts (shaderio_frame.h, VGEO_BINDING_VISIBILITY),
// written by raster_software.comp and read by resolve.comp. Needs common.glsl.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

// Readers define VGEO_VISIBILITY_ACCESS readonly before including this.
#ifndef VGEO_VISIBILITY_ACCESS
#define VGEO_VISIBILITY_ACCESS
#endif
layout(set = 0, binding = VGEO_BINDING_VISIBILITY, std430) VGEO_VISIBILITY_ACCESS buffer VisibilityBuffer { uint64_t visibility[]; };
layout(set = 0, binding = VGEO_BINDING_OVERDRAW, std430) VGEO_VISIBILITY_ACCESS buffer OverdrawBuffer { uint overdraw[]; };

uint64_t visibilityWord(float depth, uint triangleWord) {
  return (uint64_t(floatBitsToUint(depth)) << 32) | uint64_t(triangleWord);
}
