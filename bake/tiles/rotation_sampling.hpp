#pragma once
#include "bake/tiles/tile_random.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace nano::tiles {

// Uniform on SO(3) (Shoemake 1992, "Uniform random rotations").
glm::quat uniform_rotation(SplitMix64& rng);
// Shortest rotation taking unit vector `from` onto unit vector `to` (any axis when opposite).
glm::quat rotation_between(glm::vec3 from, glm::vec3 to);
glm::quat spin_about_z(double angle);

}  // namespace nano::tiles
