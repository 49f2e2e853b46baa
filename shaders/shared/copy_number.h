// The copy number of runtime/oracle/explicit_scene.hpp (Copy::number), shared by the CPU oracle
// and the renderer's shader so both name a copy by the same 64-bit integer. GLSL 460 and C++20/GLM.
// 64-bit values travel as uvec2 (x: low word, y: high word) because shaderInt64 is optional in
// Vulkan; all arithmetic is modulo 2^64 (the oracle refuses packages whose numbers would wrap).
#ifndef NANO_COPY_NUMBER_H
#define NANO_COPY_NUMBER_H
#include "shared/glsl_cpp.h"

NANO_BEGIN

NANO_FN uvec2 copy_number_add(NANO_IN(uvec2) a, NANO_IN(uvec2) b) {
  uint carry;
  uint lo = uaddCarry(a.x, b.x, carry);
  return uvec2(lo, a.y + b.y + carry);
}

NANO_FN uvec2 copy_number_mul(NANO_IN(uvec2) a, uint b) {
  uint hi;
  uint lo;
  umulExtended(a.x, b, hi, lo);
  return uvec2(lo, hi + a.y * b);
}

// base + (t_local·slots + slot)·square_instances + instance: a membrane copy of triangle t_local
// (index within its mesh), replication slot `slot` of `slots` = W·H, instance index in its Wang square.
NANO_FN uvec2 copy_number_membrane(NANO_IN(uvec2) base, uint t_local, uint slots, uint slot, uint square_instances,
                                   uint instance) {
  uvec2 cell = copy_number_add(copy_number_mul(uvec2(t_local, 0u), slots), uvec2(slot, 0u));
  return copy_number_add(copy_number_add(base, copy_number_mul(cell, square_instances)), uvec2(instance, 0u));
}

// base + membrane_span + box·cube_instances + instance: a core copy in core-grid box `box` (linear index).
NANO_FN uvec2 copy_number_core(NANO_IN(uvec2) base, NANO_IN(uvec2) membrane_span, uint box, uint cube_instances,
                               uint instance) {
  uvec2 r = copy_number_add(base, membrane_span);
  r = copy_number_add(r, copy_number_mul(uvec2(box, 0u), cube_instances));
  return copy_number_add(r, uvec2(instance, 0u));
}

NANO_END

#ifdef __cplusplus
namespace nano::gpu {
inline glm::uvec2 copy_number_words(std::uint64_t v) { return {std::uint32_t(v), std::uint32_t(v >> 32)}; }
inline std::uint64_t copy_number_value(const glm::uvec2& w) { return (std::uint64_t{w.y} << 32) | w.x; }
}  // namespace nano::gpu
#endif
#endif
