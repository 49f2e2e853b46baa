#pragma once
// The camera (common/camera.hpp) as `render`, `verify`, `bench` and the viewer take it: parsed from
// "position=x,y,z;look_at=x,y,z;up=x,y,z;fov_degrees=DEG" (scene.json's words; pos, at and fov are
// aliases) or from the package's scene record.
#include <cstdint>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "format/package.hpp"
#include "common/camera.hpp"
#include "common/error.hpp"

namespace nano::render {

// The focus distance `render`, `bench` and the viewer shade with: from the eye to the look-at point
// (RenderSettings::focus_distance: the depth cue is measured in it). One rule, so their frames stay
// identical.
float focus_distance_for(const Camera& camera);

// Keys may come in any order and any may be left out (they keep `base`'s value); a key given twice
// (also once by its alias) is an error. Throws an InputError against `source` (where the text came
// from) naming the part that does not parse.
Camera parse_camera(std::string_view text, const Camera& base, const InputSource& source);

// The package's default camera (section scene), or a view of everything when it has none.
Camera package_camera(const format::Package& package);

}  // namespace nano::render
