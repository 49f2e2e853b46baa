#include "bake/mesh/vertex_normals.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace nano::mesh {

namespace {
double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  // atan2 of |a×b| and a·b stays accurate for angles near 0 and π, unlike acos of the dot product.
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}
}  // namespace

void compute_angle_weighted_normals(ProxyMesh& mesh) {
  std::vector<glm::dvec3> sums(mesh.positions.size(), glm::dvec3(0.0));
  for (const Triangle& t : mesh.triangles) {
    const glm::dvec3 p[3] = {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
    const glm::dvec3 cross = glm::cross(p[1] - p[0], p[2] - p[0]);
    const double length = glm::length(cross);
    if (!(length > 0.0)) continue;
    const glm::dvec3 unit = cross / length;
    for (int c = 0; c < 3; ++c) {
      const glm::dvec3 e1 = p[(c + 1) % 3] - p[c];
      const glm::dvec3 e2 = p[(c + 2) % 3] - p[c];
      sums[t[c]] += angle_between(e1, e2) * unit;
    }
  }
  mesh.normals.resize(sums.size());
  for (std::size_t i = 0; i < sums.size(); ++i) {
    const double length = glm::length(sums[i]);
    mesh.normals[i] = length > 0.0 ? sums[i] / length : glm::dvec3(0.0, 0.0, 1.0);
  }
  mesh.normal_triangles = mesh.triangles;
}

}  // namespace nano::mesh
