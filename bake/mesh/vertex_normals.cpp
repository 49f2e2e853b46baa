#include "bake/mesh/vertex_normals.hpp"

#include <algorithm>
#include <array>
#include <optional>

#include "bake/mesh/uv_distortion.hpp"

#include <cmath>

#include <glm/geometric.hpp>

namespace nano::mesh {

namespace {
double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  // atan2 of |a×b| and a·b stays accurate for angles near 0 and π, unlike acos of the dot product.
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// tan of an angle from its cosine; INFINITY at 90° or more (no bound).
double tan_from_cos(double c) {
  if (!(c > 0.0)) return INFINITY;
  return std::sqrt(std::max(0.0, 1.0 - c * c)) / c;
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
  // unit_direction: a vertex whose angles are all tiny (a far outlier's) has a sum whose squares underflow.
  for (std::size_t i = 0; i < sums.size(); ++i)
    mesh.normals[i] = unit_direction(sums[i]).value_or(glm::dvec3(0.0, 0.0, 1.0));
  mesh.normal_triangles = mesh.triangles;
}

double triangle_turn_rate(const ProxyMesh& mesh, std::size_t t) {
  const std::array<glm::dvec3, 3> p{mesh.corner_position(t, 0), mesh.corner_position(t, 1), mesh.corner_position(t, 2)};
  const glm::dvec3 face = glm::cross(p[1] - p[0], p[2] - p[0]);
  if (!(glm::length(face) > 0.0) || !(glm::length(p[1] - p[0]) > 0.0)) return 0.0;
  // The triangle in its own plane: an orthonormal frame (e1, e2), so the gradient is per Å.
  const glm::dvec3 e1 = glm::normalize(p[1] - p[0]), e2 = glm::normalize(glm::cross(glm::normalize(face), e1));
  std::array<glm::dvec2, 3> plane;
  std::array<glm::dvec3, 3> n;
  for (int c = 0; c < 3; ++c) {
    plane[c] = {glm::dot(p[c] - p[0], e1), glm::dot(p[c] - p[0], e2)};
    n[c] = glm::normalize(mesh.corner_normal(t, c));
  }
  const std::optional<UvJacobian> gradient = uv_jacobian(n, plane);
  if (!gradient) return 0.0;
  double shortest = 1.0;
  for (int i = 0; i < 3; ++i) shortest = std::min(shortest, glm::length(n[i] + n[(i + 1) % 3]) / 2.0);
  if (!(shortest > 0.0)) return 0.0;  // opposite corner normals: no bound from this triangle
  return singular_values(*gradient).major / shortest;
}

double normal_turn_rate(const ProxyMesh& mesh) {
  double rate = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) rate = std::max(rate, triangle_turn_rate(mesh, t));
  return rate;
}

double triangle_facet_sag(const ProxyMesh& mesh, std::size_t t) {
  const glm::dvec3 centroid = (mesh.corner_position(t, 0) + mesh.corner_position(t, 1) + mesh.corner_position(t, 2)) / 3.0;
  double reach = 0.0;
  for (int c = 0; c < 3; ++c) reach = std::max(reach, glm::length(mesh.corner_position(t, c) - centroid));
  return 0.5 * reach * reach * triangle_turn_rate(mesh, t);
}

double largest_facet_sag(const ProxyMesh& mesh) {
  double sag = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) sag = std::max(sag, triangle_facet_sag(mesh, t));
  return sag;
}

double largest_normal_tilt(const ProxyMesh& mesh) {
  double smallest_cos = 1.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::dvec3 face =
        glm::cross(mesh.corner_position(t, 1) - mesh.corner_position(t, 0), mesh.corner_position(t, 2) - mesh.corner_position(t, 0));
    if (!(glm::length(face) > 0.0)) continue;
    for (int c = 0; c < 3; ++c)
      smallest_cos = std::min(smallest_cos, glm::dot(glm::normalize(face), glm::normalize(mesh.corner_normal(t, c))));
  }
  return tan_from_cos(smallest_cos);  // a normal at 90° or more from its face: no bound
}

double triangle_smooth_normal_tilt(const ProxyMesh& mesh, std::size_t t, double smooth) {
  constexpr int kSteps = 8;  // barycentric grid: corners, edge points and inner points
  constexpr double kStep = 1e-5;
  const glm::dvec3 P[3] = {mesh.corner_position(t, 0), mesh.corner_position(t, 1), mesh.corner_position(t, 2)};
  const glm::dvec3 face = glm::cross(P[1] - P[0], P[2] - P[0]);
  if (!(glm::length(face) > 0.0)) return 0.0;
  glm::dvec3 m[3];
  for (int c = 0; c < 3; ++c) m[c] = glm::normalize(mesh.corner_normal(t, c));
  // Phong tessellation at barycentrics (1 − a − b, a, b), as the shaders place copies.
  const auto surface = [&](double a, double b) {
    const double l[3] = {1.0 - a - b, a, b};
    const glm::dvec3 p = l[0] * P[0] + l[1] * P[1] + l[2] * P[2];
    glm::dvec3 lift(0.0);
    for (int c = 0; c < 3; ++c) lift += l[c] * glm::dot(p - P[c], m[c]) * m[c];
    return p - smooth * lift;
  };
  double smallest_cos = 1.0;
  for (int i = 0; i <= kSteps; ++i)
    for (int j = 0; i + j <= kSteps; ++j) {
      const double a = double(i) / kSteps, b = double(j) / kSteps;
      // One-sided differences that stay inside the triangle (the overhang is not sampled).
      const double da = i + j < kSteps ? kStep : -kStep, db = i + j < kSteps ? kStep : -kStep;
      const glm::dvec3 x = surface(a, b);
      glm::dvec3 normal = glm::cross((surface(a + da, b) - x) / da, (surface(a, b + db) - x) / db);
      if (!(glm::length(normal) > 0.0)) continue;
      if (glm::dot(normal, face) < 0.0) normal = -normal;
      const double l[3] = {1.0 - a - b, a, b};
      const glm::dvec3 interpolated = glm::normalize(l[0] * m[0] + l[1] * m[1] + l[2] * m[2]);
      smallest_cos = std::min(smallest_cos, glm::dot(glm::normalize(normal), interpolated));
    }
  return tan_from_cos(smallest_cos);
}

double largest_smooth_normal_tilt(const ProxyMesh& mesh, double smooth) {
  double tilt = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) tilt = std::max(tilt, triangle_smooth_normal_tilt(mesh, t, smooth));
  return tilt;
}

double offset_surface_area(const ProxyMesh& mesh, double distance) {
  double area = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    std::array<glm::dvec3, 3> p;
    for (int c = 0; c < 3; ++c)
      p[c] = mesh.corner_position(t, c) + (mesh.has_normals() ? distance * mesh.corner_normal(t, c) : glm::dvec3(0.0));
    area += 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
  }
  return area;
}

}  // namespace nano::mesh
