#include "bake/scene/transform.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace nano::scene {
namespace {

using Linear = std::array<glm::dvec3, 3>;  // rows of a 3×3 matrix

Matrix3x4 from_linear(const Linear& a, const glm::dvec3& t) {
  return {glm::dvec4(a[0], t.x), glm::dvec4(a[1], t.y), glm::dvec4(a[2], t.z)};
}

Linear linear_part(const Matrix3x4& m) {
  return {glm::dvec3(m[0]), glm::dvec3(m[1]), glm::dvec3(m[2])};
}

// Largest eigenvalue of a symmetric 3×3 matrix, closed form (Smith 1961): exact up to
// rounding, with no iteration count to tune.
double largest_symmetric_eigenvalue(const Linear& a) {
  const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
  if (off == 0.0) return std::max({a[0][0], a[1][1], a[2][2]});
  const double q = (a[0][0] + a[1][1] + a[2][2]) / 3.0;
  const double p2 = (a[0][0] - q) * (a[0][0] - q) + (a[1][1] - q) * (a[1][1] - q) +
                    (a[2][2] - q) * (a[2][2] - q) + 2.0 * off;
  const double p = std::sqrt(p2 / 6.0);
  Linear b = a;
  for (int i = 0; i < 3; ++i) {
    b[i] /= p;
    b[i][i] -= q / p;
  }
  const double r = glm::dot(b[0], glm::cross(b[1], b[2])) / 2.0;
  const double phi = r <= -1.0 ? std::numbers::pi / 3.0 : r >= 1.0 ? 0.0 : std::acos(r) / 3.0;
  return q + 2.0 * p * std::cos(phi);
}

}  // namespace

Matrix3x4 identity_transform() {
  return {glm::dvec4(1, 0, 0, 0), glm::dvec4(0, 1, 0, 0), glm::dvec4(0, 0, 1, 0)};
}

Matrix3x4 translate_rotate_scale(const glm::dvec3& translate, const glm::dvec3& axis, double degrees, double scale) {
  const glm::dvec3 u = glm::normalize(axis);
  const double angle = degrees * std::numbers::pi / 180.0;
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  // Rodrigues' rotation formula, times the uniform scale.
  const Linear r = {
      glm::dvec3(t * u.x * u.x + c, t * u.x * u.y - s * u.z, t * u.x * u.z + s * u.y) * scale,
      glm::dvec3(t * u.x * u.y + s * u.z, t * u.y * u.y + c, t * u.y * u.z - s * u.x) * scale,
      glm::dvec3(t * u.x * u.z - s * u.y, t * u.y * u.z + s * u.x, t * u.z * u.z + c) * scale,
  };
  return from_linear(r, translate);
}

Matrix3x4 rigid_transform(const glm::dvec4& q, const glm::dvec3& translate) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const Linear r = {
      glm::dvec3(1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)),
      glm::dvec3(2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)),
      glm::dvec3(2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)),
  };
  return from_linear(r, translate);
}

glm::dvec3 transform_point(const Matrix3x4& m, const glm::dvec3& p) {
  const glm::dvec4 h(p, 1.0);
  return {glm::dot(m[0], h), glm::dot(m[1], h), glm::dot(m[2], h)};
}

double linear_determinant(const Matrix3x4& m) {
  const Linear a = linear_part(m);
  return glm::dot(a[0], glm::cross(a[1], a[2]));
}

double largest_stretch(const Matrix3x4& m) {
  const Linear a = linear_part(m);
  Linear ata{};  // AᵀA: its eigenvalues are the squared singular values of A
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) ata[i][j] = a[0][i] * a[0][j] + a[1][i] * a[1][j] + a[2][i] * a[2][j];
  return std::sqrt(std::max(0.0, largest_symmetric_eigenvalue(ata)));
}

}  // namespace nano::scene
