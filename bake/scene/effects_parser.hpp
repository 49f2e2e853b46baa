#pragma once
// The "effects" and "camera" members of scene.json.
#include <cstddef>

#include "common/json_cursor.hpp"
#include "bake/scene/scene_description.hpp"

namespace nano::scene {

// `instance_count`: instances after random expansion, the range of keyframe "instance" indices.
Effects parse_effects(const JsonCursor& effects, std::size_t instance_count);

Camera parse_camera(const JsonCursor& camera);

// A box [[xmin, ymin, zmin], [xmax, ymax, zmax]] with min < max on every axis.
Box parse_box(const JsonCursor& box);

}  // namespace nano::scene
