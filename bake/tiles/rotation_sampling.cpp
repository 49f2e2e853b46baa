#include "bake/tiles/rotation_sampling.hpp"

#include <cmath>

namespace nano::tiles {

glm::quat uniform_rotation(SplitMix64& rng) {
  const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  const double two_pi = 2.0 * M_PI;
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  return glm::normalize(glm::quat(static_cast<float>(b * std::cos(two_pi * u3)),
                                  static_cast<float>(a * std::sin(two_pi * u2)),
                                  static_cast<float>(a * std::cos(two_pi * u2)),
                                  static_cast<float>(b * std::sin(two_pi * u3))));
}

glm::quat rotation_between(glm::vec3 from, glm::vec3 to) {
  from = glm::normalize(from);
  to = glm::normalize(to);
  const float c = glm::dot(from, to);
  if (c < -1.f + 1e-6f) {
    // Opposite: half turn about any axis perpendicular to `from`.
    glm::vec3 axis = glm::cross(from, glm::vec3(1.f, 0.f, 0.f));
    if (glm::dot(axis, axis) < 1e-6f) axis = glm::cross(from, glm::vec3(0.f, 1.f, 0.f));
    axis = glm::normalize(axis);
    return glm::quat(0.f, axis.x, axis.y, axis.z);
  }
  const glm::vec3 axis = glm::cross(from, to);
  return glm::normalize(glm::quat(1.f + c, axis.x, axis.y, axis.z));
}

glm::quat spin_about_z(double angle) {
  return glm::quat(static_cast<float>(std::cos(0.5 * angle)), 0.f, 0.f,
                   static_cast<float>(std::sin(0.5 * angle)));
}

}  // namespace nano::tiles
