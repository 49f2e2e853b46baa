// The parts of remeshing that need no CGAL: when to remesh, to what, and the account of it.
#include "bake/mesh/mesh_remesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "bake/mesh/mesh_edges.hpp"
#include "bake/mesh/uv_distortion.hpp"

namespace nano::mesh {

namespace {

constexpr double kDegreesPerRadian = 57.29577951308232;

// An equilateral triangle of edge L has area √3/4·L².
constexpr double kEquilateralAreaFactor = 0.4330127018922193;

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

}  // namespace

RemeshOptions membrane_remesh_options(const ProxyMesh& mesh, double bilayer_thickness) {
  double area = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) area += world_area(mesh, t);
  const double edge_for_count = std::sqrt(area / (kEquilateralAreaFactor * double(kRemeshMaxTriangles)));
  RemeshOptions options;
  options.edge = std::max(0.5 * bilayer_thickness, edge_for_count);
  options.max_distance = std::max(bilayer_thickness, options.edge) + 0.25 * options.edge;
  options.crease_radius = kCreaseRadiusBilayers * bilayer_thickness;
  return options;
}

double largest_crease_degrees(const ProxyMesh& mesh) {
  std::vector<glm::dvec3> normals(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::dvec3 p0 = mesh.corner_position(t, 0);
    const glm::dvec3 n = glm::cross(mesh.corner_position(t, 1) - p0, mesh.corner_position(t, 2) - p0);
    const double length = glm::length(n);
    normals[t] = length > 0.0 ? n / length : glm::dvec3(0.0);
  }
  double largest = 0.0;
  for (const MeshEdge& e : collect_edges(mesh)) {
    if (e.uses.size() != 2) continue;
    const glm::dvec3& a = normals[e.uses[0].face];
    const glm::dvec3& b = normals[e.uses[1].face];
    if (a == glm::dvec3(0.0) || b == glm::dvec3(0.0)) continue;
    largest = std::max(largest, std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * kDegreesPerRadian);
  }
  return largest;
}

std::optional<std::string> remesh_reason(const ProxyMesh& mesh) {
  const double crease = largest_crease_degrees(mesh);
  if (crease <= kRemeshCreaseDegrees) return std::nullopt;
  return format("neighbouring faces turn by up to %.1f°", crease) +
         format(" (a bilayer's shells follow at most %.0f°)", kRemeshCreaseDegrees);
}

nlohmann::json to_json(const RemeshReport& r) {
  return {{"reason", r.reason},
          {"triangles_in", r.triangles_in},
          {"triangles_out", r.triangles_out},
          {"edge_A", r.edge},
          {"distance_bound_A", r.distance_bound},
          {"max_distance_A", r.max_distance},
          {"largest_crease_in_degrees", r.largest_crease_in},
          {"largest_crease_out_degrees", r.largest_crease_out},
          {"largest_normal_deviation_degrees", r.largest_normal_deviation},
          {"area_in_A2", r.area_in},
          {"area_out_A2", r.area_out},
          {"volume_in_A3", r.volume_in},
          {"volume_out_A3", r.volume_out},
          {"smoothing_steps", r.smoothing_steps}};
}

std::string describe(const RemeshReport& r) {
  std::string s = "remeshed (" + r.reason + "): " + std::to_string(r.triangles_in) + " -> " +
                  std::to_string(r.triangles_out) + " triangles" + format(", edge %.1f Å", r.edge);
  s += format("; creases %.1f°", r.largest_crease_in) + format(" -> %.1f°", r.largest_crease_out);
  s += format("; within %.1f Å", r.max_distance) + format(" of the input (bound %.1f Å)", r.distance_bound);
  s += format("; normals turned by up to %.1f°", r.largest_normal_deviation);
  if (r.area_in > 0.0) s += format("; area %+.2f %%", 100.0 * (r.area_out / r.area_in - 1.0));
  if (r.volume_in > 0.0) s += format(", volume %+.2f %%", 100.0 * (r.volume_out / r.volume_in - 1.0));
  return s;
}

}  // namespace nano::mesh
