#pragma once
// The placement transform of an instance or keyframe object: its optional "transform"
// ({translate, rotate {axis, degrees}, scale}) or "matrix" (3 rows of 4 numbers) member.
#include "common/json_cursor.hpp"
#include "bake/scene/transform.hpp"

namespace nano::scene {

// Reads `owner.transform` or `owner.matrix` (at most one; neither is the identity). The linear
// part must have a positive determinant: a mirror would turn membranes inside out.
Matrix3x4 parse_placement_transform(const JsonCursor& owner);

}  // namespace nano::scene
