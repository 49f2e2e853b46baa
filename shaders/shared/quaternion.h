// Quaternion helpers shared by GLSL and C++. A quaternion is a vec4 (x, y, z, w) with xyz the
// vector part and w the scalar part (the order of the package's instance records and of GLSL
// convention; NOT glm::quat's constructor order). Rotations use unit quaternions.
#ifndef NANO_QUATERNION_H
#define NANO_QUATERNION_H
#include "shared/placement_common.h"

NANO_BEGIN

// Identity rotation (0, 0, 0, 1).
NANO_FN vec4 quat_identity() { return vec4(0.0f, 0.0f, 0.0f, 1.0f); }

// Hamilton product a·b: rotating by the result = rotate by b first, then by a.
NANO_FN vec4 quat_mul(NANO_IN(vec4) a, NANO_IN(vec4) b) {
  return vec4(a.w * vec3(b) + b.w * vec3(a) + cross(vec3(a), vec3(b)), a.w * b.w - dot(vec3(a), vec3(b)));
}

// Conjugate (the inverse for a unit quaternion).
NANO_FN vec4 quat_conjugate(NANO_IN(vec4) q) { return vec4(-q.x, -q.y, -q.z, q.w); }

// Unit quaternion rotating by `angle` radians about `axis` (any non-zero length; normalised here),
// right-handed (counter-clockwise looking down the axis towards the origin).
NANO_FN vec4 quat_from_axis_angle(NANO_IN(vec3) axis, float angle) {
  float h = 0.5f * angle;
  return vec4(normalize(axis) * sin(h), cos(h));
}

// Rotates v by the unit quaternion q (q v q*), in the numerically good form
// v + 2w(u×v) + 2u×(u×v). Error ≈ a few ulps of |v| for |q| = 1.
NANO_FN vec3 quat_rotate(NANO_IN(vec4) q, NANO_IN(vec3) v) {
  vec3 u = vec3(q);
  vec3 c = cross(u, v);
  return v + 2.0f * (q.w * c + cross(u, c));
}

// Rotation matrix (column-major mat3) of the unit quaternion q: quat_to_mat3(q) * v == quat_rotate(q, v).
NANO_FN mat3 quat_to_mat3(NANO_IN(vec4) q) {
  float x = q.x; float y = q.y; float z = q.z; float w = q.w;
  return mat3(1.0f - 2.0f * (y * y + z * z), 2.0f * (x * y + w * z), 2.0f * (x * z - w * y),
              2.0f * (x * y - w * z), 1.0f - 2.0f * (x * x + z * z), 2.0f * (y * z + w * x),
              2.0f * (x * z + w * y), 2.0f * (y * z - w * x), 1.0f - 2.0f * (x * x + y * y));
}

NANO_END
#endif
