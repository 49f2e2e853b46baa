#pragma once
// Affine placement transforms as the package stores them: 3×4 row-major, object -> world,
// p' = M·(p, 1). Double precision here; the package narrows to float at write time.
#include <array>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace nano::scene {

using Matrix3x4 = std::array<glm::dvec4, 3>;  // rows

Matrix3x4 identity_transform();

// Scale (uniform, about the origin), then rotate `degrees` counter-clockwise about `axis`
// (right-hand rule; need not be unit length, must be non-zero), then translate.
Matrix3x4 translate_rotate_scale(const glm::dvec3& translate, const glm::dvec3& axis, double degrees, double scale);

// Rotation by a unit quaternion (w, x, y, z) followed by a translation.
Matrix3x4 rigid_transform(const glm::dvec4& unit_quaternion_wxyz, const glm::dvec3& translate);

glm::dvec3 transform_point(const Matrix3x4& m, const glm::dvec3& p);

// Determinant of the 3×3 linear part: > 0 keeps handedness (and so outward normals).
double linear_determinant(const Matrix3x4& m);

// The largest factor by which the linear part stretches any vector (its largest singular value),
// i.e. how much a bounding sphere's radius grows under the transform.
double largest_stretch(const Matrix3x4& m);

}  // namespace nano::scene
