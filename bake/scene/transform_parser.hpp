#pragma once
// The placement transform of an instance or keyframe object: its optional "transform"
// ({translate, rotate {axis, degrees}, scale}) or "matrix" (3 rows of 4 numbers) member.
#include "common/json_cursor.hpp"
#include "bake/scene/transform.hpp"

namespace nano::scene {

// The same vector scaled by the power of two that brings its largest component into [1, 2).
// Exact, so whatever is normalised from it has the bits it had from `v` (when that did not
// overflow), yet one written as [1e-200, 0, 0] or [1e300, 1e300, 0] no longer under- or overflows.
// `v` must not be zero.
glm::dvec3 rescaled_by_power_of_two(const glm::dvec3& v);

// Reads `owner.transform` or `owner.matrix` (at most one; neither is the identity). The linear
// part must have a positive determinant: a mirror would turn membranes inside out.
Matrix3x4 parse_placement_transform(const JsonCursor& owner);

}  // namespace nano::scene
