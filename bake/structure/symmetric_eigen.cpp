#include "bake/structure/symmetric_eigen.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace nano::structure {

glm::dvec3 canonical_sign(const glm::dvec3& v) {
  int largest = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(v[i]) > std::abs(v[largest])) largest = i;
  return v[largest] < 0.0 ? -v : v;
}

SymmetricEigen symmetric_eigen(const glm::dmat3& m) {
  // a[r][c] row-major copy; glm is column-major, and m[c][r] is column c, row r.
  double a[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a[r][c] = r <= c ? m[c][r] : m[r][c];
  double v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

  for (int sweep = 0; sweep < 64; ++sweep) {
    const double off = std::abs(a[0][1]) + std::abs(a[0][2]) + std::abs(a[1][2]);
    const double diagonal = std::abs(a[0][0]) + std::abs(a[1][1]) + std::abs(a[2][2]);
    if (off == 0.0 || off <= 1e-300 || diagonal + off == diagonal) break;
    for (int p = 0; p < 2; ++p) {
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0.0) continue;
        // Rotation angle chosen so that a[p][q] becomes zero (Numerical Recipes' stable form).
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0);
        const double s = t * c;
        for (int k = 0; k < 3; ++k) {  // columns p, q of A·J
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {  // rows p, q of Jᵀ·(A·J)
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        a[p][q] = a[q][p] = 0.0;
        for (int k = 0; k < 3; ++k) {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }

  std::array<int, 3> order{0, 1, 2};
  std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return a[i][i] > a[j][j]; });
  SymmetricEigen result;
  for (int i = 0; i < 3; ++i) {
    const int k = order[i];
    result.values[i] = a[k][k];
    result.vectors[i] = canonical_sign(glm::normalize(glm::dvec3(v[0][k], v[1][k], v[2][k])));
  }
  return result;
}

}  // namespace nano::structure
