#include "bake/mesh/uv_distortion.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace nano::mesh {

double world_area(const ProxyMesh& mesh, std::size_t t) {
  const glm::dvec3 p0 = mesh.corner_position(t, 0);
  return 0.5 * glm::length(glm::cross(mesh.corner_position(t, 1) - p0, mesh.corner_position(t, 2) - p0));
}

double uv_signed_area(const ProxyMesh& mesh, std::size_t t) {
  const glm::dvec2 a = mesh.corner_uv(t, 1) - mesh.corner_uv(t, 0);
  const glm::dvec2 b = mesh.corner_uv(t, 2) - mesh.corner_uv(t, 0);
  return 0.5 * (a.x * b.y - a.y * b.x);
}

std::optional<UvJacobian> uv_jacobian(const std::array<glm::dvec3, 3>& world,
                                      const std::array<glm::dvec2, 3>& uv) {
  const glm::dvec3 f1 = world[1] - world[0], f2 = world[2] - world[0];
  const glm::dvec2 e1 = uv[1] - uv[0], e2 = uv[2] - uv[0];
  const double det = e1.x * e2.y - e2.x * e1.y;
  if (det == 0.0) return std::nullopt;
  // E⁻¹ = [[e2.y, −e2.x], [−e1.y, e1.x]] / det; J = F·E⁻¹ column by column.
  return UvJacobian{(f1 * e2.y - f2 * e1.y) / det, (f2 * e1.x - f1 * e2.x) / det};
}

std::optional<UvJacobian> uv_jacobian(const ProxyMesh& mesh, std::size_t t) {
  return uv_jacobian({mesh.corner_position(t, 0), mesh.corner_position(t, 1), mesh.corner_position(t, 2)},
                     {mesh.corner_uv(t, 0), mesh.corner_uv(t, 1), mesh.corner_uv(t, 2)});
}

SingularValues singular_values(const UvJacobian& j) {
  const double a = glm::dot(j.du, j.du), b = glm::dot(j.du, j.dv), c = glm::dot(j.dv, j.dv);
  // Eigenvalues of [[a, b], [b, c]]: mean ± sqrt(((a−c)/2)² + b²); hypot avoids cancellation.
  const double mean = 0.5 * (a + c);
  const double radius = std::hypot(0.5 * (a - c), b);
  return {std::sqrt(mean + radius), std::sqrt(std::max(0.0, mean - radius))};
}

double uv_scale(const ProxyMesh& mesh) {
  double world = 0.0, uv = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    world += world_area(mesh, t);
    uv += std::abs(uv_signed_area(mesh, t));
  }
  return uv > 0.0 ? std::sqrt(world / uv) : 0.0;
}

namespace {
// The extreme singular values over triangles with a usable chart (σ2 > 0); {0, 0} without any.
SingularValues stretch_range(const ProxyMesh& mesh) {
  SingularValues range;
  bool any = false;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const std::optional<UvJacobian> j = uv_jacobian(mesh, t);
    if (!j) continue;
    const SingularValues s = singular_values(*j);
    if (!(s.minor > 0.0)) continue;
    range.minor = any ? std::min(range.minor, s.minor) : s.minor;
    range.major = any ? std::max(range.major, s.major) : s.major;
    any = true;
  }
  return range;
}
}  // namespace

double smallest_stretch(const ProxyMesh& mesh) { return stretch_range(mesh).minor; }

double chart_anisotropy(const ProxyMesh& mesh) {
  const SingularValues range = stretch_range(mesh);
  return range.minor > 0.0 ? range.major / range.minor : 0.0;
}

int tiles_spanning(double extent, double s) { return static_cast<int>(std::ceil(extent / s)) + 1; }

std::array<int, 2> triangle_tile_span(const ProxyMesh& mesh, std::size_t t, double s) {
  const glm::dvec2 a = mesh.corner_uv(t, 0), b = mesh.corner_uv(t, 1), c = mesh.corner_uv(t, 2);
  const glm::dvec2 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
  return {tiles_spanning(hi.x - lo.x, s), tiles_spanning(hi.y - lo.y, s)};
}

std::array<int, 2> replication_area(const ProxyMesh& mesh, double s) {
  std::array<int, 2> area{0, 0};
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto span = triangle_tile_span(mesh, t, s);
    area = {std::max(area[0], span[0]), std::max(area[1], span[1])};
  }
  return area;
}

}  // namespace nano::mesh
