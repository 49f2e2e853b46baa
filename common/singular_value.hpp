#pragma once
// Largest singular value of a 3×3 matrix: how far a linear map can stretch a unit vector, so how
// much it grows a bounding sphere's radius. Shared by the oracle (instance stretch) and the
// renderer (tile-space bounds of membrane molecules).
#include <algorithm>
#include <cmath>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace nano {

// sqrt of the largest eigenvalue of LᵀL, by Smith's closed form for symmetric 3×3 matrices.
inline double largest_singular_value(const glm::dmat3& l) {
  const glm::dmat3 m = glm::transpose(l) * l;
  const double p1 = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
  if (p1 == 0) return std::sqrt(std::max({m[0][0], m[1][1], m[2][2]}));
  const double q = (m[0][0] + m[1][1] + m[2][2]) / 3;
  const double p2 = (m[0][0] - q) * (m[0][0] - q) + (m[1][1] - q) * (m[1][1] - q) + (m[2][2] - q) * (m[2][2] - q) + 2 * p1;
  const double p = std::sqrt(p2 / 6);
  const double r = std::clamp(glm::determinant((m - q * glm::dmat3(1.0)) / p) / 2, -1.0, 1.0);
  return std::sqrt(q + 2 * p * std::cos(std::acos(r) / 3));
}

}  // namespace nano
