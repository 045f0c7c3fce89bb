// shaderio_core.h: what lets one header be both C++ and GLSL. In C++ the shared declarations live in
// namespace shaderio with glm's types under GLSL's names; VGEO_INLINE, VGEO_OUT and VGEO_INOUT spell a
// function and its out / inout parameters in both languages. Code between VGEO_NAMESPACE_BEGIN and
// VGEO_NAMESPACE_END, written in the subset both compile, runs the same arithmetic on the host and the GPU.
#ifndef VGEO_SHADERIO_CORE_H
#define VGEO_SHADERIO_CORE_H

#ifdef __cplusplus
#include <bit>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#define VGEO_NAMESPACE_BEGIN namespace shaderio {
#define VGEO_NAMESPACE_END }
#define VGEO_INLINE inline
#define VGEO_OUT(T) T&
#define VGEO_OUT_ARRAY(T, name, n) T(&name)[n]
#define VGEO_INOUT(T) T&
namespace shaderio {
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec2 = glm::uvec2;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using uint = uint32_t;
using glm::abs;
using glm::cross;
using glm::dot;
using glm::length;
using glm::max;
using glm::mix;
using glm::normalize;
// GLSL's bit cast, for the host.
inline float uintBitsToFloat(uint bits) {
  float f;
  static_assert(sizeof(f) == sizeof(bits), "float size");
  __builtin_memcpy(&f, &bits, 4);
  return f;
}
}  // namespace shaderio
#else
#define VGEO_NAMESPACE_BEGIN
#define VGEO_NAMESPACE_END
#define VGEO_INLINE
#define VGEO_OUT(T) out T
#define VGEO_OUT_ARRAY(T, name, n) out T name[n]
#define VGEO_INOUT(T) inout T
#endif

#endif
