// visibility.glsl: the visibility buffer and the overdraw counts (shaderio_frame.h, VGEO_BINDING_VISIBILITY),
// written by the compute rasterizers (raster_triangle.glsl) and read by resolve.comp. Needs common.glsl.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require

// Readers define VGEO_VISIBILITY_ACCESS readonly before including this.
#ifndef VGEO_VISIBILITY_ACCESS
#define VGEO_VISIBILITY_ACCESS
#endif
layout(set = 0, binding = VGEO_BINDING_VISIBILITY, std430) VGEO_VISIBILITY_ACCESS buffer VisibilityBuffer { uint64_t visibility[]; };
layout(set = 0, binding = VGEO_BINDING_OVERDRAW, std430) VGEO_VISIBILITY_ACCESS buffer OverdrawBuffer { uint overdraw[]; };

// A pixel's word: the depth's float bits (in [0, 1], so below 2^30) above an id of
// VGEO_VISIBILITY_ID_BITS bits.
uint64_t visibilityWord(float depth, uint64_t id) {
  return (uint64_t(floatBitsToUint(clamp(depth, 0.0, 1.0))) << VGEO_VISIBILITY_ID_BITS) | id;
}
float visibilityDepth(uint64_t word) { return uintBitsToFloat(uint(word >> VGEO_VISIBILITY_ID_BITS)); }
uint64_t visibilityId(uint64_t word) { return word & ((uint64_t(1) << VGEO_VISIBILITY_ID_BITS) - 1ul); }

// The id of micro-triangle `triangle` of the patch in slot `slot` of the patch list.
uint64_t patchTriangleId(uint slot, uint triangle) {
  return VGEO_VISIBILITY_PATCH_BIT | (uint64_t(slot) << VGEO_PATCH_TRIANGLE_BITS) | uint64_t(triangle);
}
