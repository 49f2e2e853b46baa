// The per-molecule and per-ray math of the scene effects (runtime/render/effects.hpp), shared by the
// renderer (shaders/render/render.comp) and the CPU oracle (runtime/oracle/), so a jittered or
// clipped frame can be checked against explicit instancing with the very same functions.
#ifndef NANO_EFFECTS_H
#define NANO_EFFECTS_H
#include "shared/placement_common.h"
#include "shared/quaternion.h"

NANO_BEGIN

// A 32-bit integer hash with good avalanche (Wellons' "lowbias32"); deterministic on every device.
NANO_FN uint effect_hash(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// Uniform in [0, 1) from the top 24 bits (exact in float).
NANO_FN float effect_unit(uint h) { return float(h >> 8) * (1.0f / 16777216.0f); }

// The jitter of one molecule copy at `time` (s): a rotation about the copy's own origin by
// amplitude·sin(2π(f·t + φ)) radians about a random axis; axis and phase φ come from the copy
// number, so every copy wobbles on its own and the same copy wobbles alike in every renderer.
// Rotating about the origin keeps every atom inside the copy's bounding sphere, which the mLAS boxes
// already bound: jitter needs no acceleration-structure update.
NANO_FN vec4 jitter_rotation(NANO_IN(uvec2) copy_number, float time, float amplitude_radians, float frequency_hz) {
  uint h0 = effect_hash(copy_number.x ^ effect_hash(copy_number.y + 0x9e3779b9u));
  uint h1 = effect_hash(h0 + 1u);
  uint h2 = effect_hash(h0 + 2u);
  float z = 2.0f * effect_unit(h0) - 1.0f;
  float phi = 6.28318530718f * effect_unit(h1);
  float s = sqrt(max(0.0f, 1.0f - z * z));
  vec3 axis = vec3(s * cos(phi), s * sin(phi), z);
  // fract keeps the argument of sin small however long the animation runs.
  float cycles = fract(frequency_hz * time + effect_unit(h2));
  return quat_from_axis_angle(axis, amplitude_radians * sin(6.28318530718f * cycles));
}

// The placement of a jittered copy: rotate in molecule space first, then place.
NANO_FN Affine3 jitter_placement(NANO_IN(Affine3) m, NANO_IN(vec4) rotation) {
  Affine3 r;
  r.linear = m.linear * quat_to_mat3(rotation);
  r.translation = m.translation;
  return r;
}

// Clipping half-space (unit n, d): a point p stays iff n·p + d ≥ 0.
NANO_FN bool clip_keeps_point(NANO_IN(vec4) plane, NANO_IN(vec3) p) { return dot(vec3(plane), p) + plane.w >= 0.0f; }
// True iff the whole ball (centre, radius) lies where the half-space removes points.
NANO_FN bool clip_removes_ball(NANO_IN(vec4) plane, NANO_IN(vec3) centre, float radius) {
  return dot(vec3(plane), centre) + plane.w < -radius;
}

// Wächter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection" (Ray Tracing Gems,
// ch. 6): move a surface point off the surface along its normal by a few ulps of its own magnitude
// (a fixed tiny step near the origin, where ulps vanish), so secondary rays neither start inside
// the surface they leave nor skip a nearby one, at any distance from the origin.
NANO_FN vec3 offset_ray_origin(NANO_IN(vec3) p, NANO_IN(vec3) n) {
  const float origin = 1.0f / 32.0f;
  const float float_scale = 1.0f / 65536.0f;
  const float int_scale = 256.0f;
  ivec3 of_i = ivec3(int_scale * n);
  vec3 p_i = vec3(intBitsToFloat(floatBitsToInt(p.x) + (p.x < 0.0f ? -of_i.x : of_i.x)),
                  intBitsToFloat(floatBitsToInt(p.y) + (p.y < 0.0f ? -of_i.y : of_i.y)),
                  intBitsToFloat(floatBitsToInt(p.z) + (p.z < 0.0f ? -of_i.z : of_i.z)));
  return vec3(abs(p.x) < origin ? p.x + float_scale * n.x : p_i.x,
              abs(p.y) < origin ? p.y + float_scale * n.y : p_i.y,
              abs(p.z) < origin ? p.z + float_scale * n.z : p_i.z);
}

// Cosine-weighted direction about the unit normal n from two uniforms in [0, 1).
NANO_FN vec3 cosine_hemisphere(NANO_IN(vec3) n, float u1, float u2) {
  vec3 helper = abs(n.x) < 0.5f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
  vec3 t = normalize(cross(n, helper));
  vec3 b = cross(n, t);
  float r = sqrt(u1);
  float phi = 6.28318530718f * u2;
  return normalize(r * cos(phi) * t + r * sin(phi) * b + sqrt(max(0.0f, 1.0f - u1)) * n);
}

NANO_END
#endif
