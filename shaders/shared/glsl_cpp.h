// Prelude that lets one header compile both as GLSL and as C++ (through GLM), so the CPU oracle,
// the baker and the tests run the very same structs and placement math as the shaders.
#ifndef NANO_GLSL_CPP_H
#define NANO_GLSL_CPP_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#define NANO_BEGIN namespace nano::gpu { using namespace glm; using uint = std::uint32_t;
#define NANO_END }
// GLSL has `inout`/`in`/`out` parameter qualifiers; in C++ they become references or nothing.
#define NANO_INOUT(T) T&
#define NANO_OUT(T) T&
#define NANO_IN(T) const T&
#define NANO_CONST constexpr
#define NANO_STATIC_ASSERT(cond, msg) static_assert(cond, msg)
// Functions defined in shared headers are included by many translation units.
#define NANO_FN inline
// GLSL `precise` forbids fma contraction and reassociation where a value decides a sign; the C++
// side gets the same guarantee from -ffp-contract=off, set for the whole project.
#define NANO_PRECISE
#else
#define NANO_BEGIN
#define NANO_END
#define NANO_INOUT(T) inout T
#define NANO_OUT(T) out T
#define NANO_IN(T) in T
#define NANO_CONST const
#define NANO_STATIC_ASSERT(cond, msg)
#define NANO_FN
#define NANO_PRECISE precise
#endif

#endif
