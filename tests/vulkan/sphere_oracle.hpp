#pragma once
// Analytic ray/sphere answers in extended precision: the independent reference the GPU is judged by.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>
#include <optional>

namespace nano::test {

struct SphereAnswer {
  std::optional<double> t;         // nearest hit in [t_min, t_max]
  double silhouette_distance = 0;  // |perpendicular distance of the centre to the ray line - r|
  double half_chord = 0;           // sqrt(r^2 - p^2)/|d| when the line meets the sphere, else 0
};

inline SphereAnswer intersect_sphere(const glm::dvec3& origin, const glm::dvec3& direction, const glm::dvec3& centre,
                                     double radius, double t_min, double t_max) {
  // Plain quadratic a t^2 + 2 b t + c = 0 in long double: no cleverness to share bugs with the shader.
  using real = long double;
  const real fx = origin.x - centre.x, fy = origin.y - centre.y, fz = origin.z - centre.z;
  const real dx = direction.x, dy = direction.y, dz = direction.z;
  const real a = dx * dx + dy * dy + dz * dz;
  const real b = fx * dx + fy * dy + fz * dz;
  const real c = fx * fx + fy * fy + fz * fz - static_cast<real>(radius) * radius;
  const real f2 = fx * fx + fy * fy + fz * fz;
  const real perpendicular = std::sqrt(std::max<real>(f2 - b * b / a, 0));

  SphereAnswer answer;
  answer.silhouette_distance = static_cast<double>(std::fabs(perpendicular - radius));
  const real discriminant = b * b - a * c;
  if (discriminant < 0) return answer;
  const real root = std::sqrt(discriminant);
  answer.half_chord = static_cast<double>(root / a);
  for (real t : {(-b - root) / a, (-b + root) / a})
    if (t >= t_min && t <= t_max) {
      answer.t = static_cast<double>(t);
      break;
    }
  return answer;
}

}  // namespace nano::test
