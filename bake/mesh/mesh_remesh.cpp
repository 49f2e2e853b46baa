// The parts of remeshing that need no CGAL: when to remesh, to what, and the account of it.
#include "bake/mesh/mesh_remesh.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "bake/mesh/mesh_edges.hpp"
#include "bake/mesh/number_text.hpp"
#include "bake/mesh/uv_distortion.hpp"

namespace nano::mesh {

namespace {

// An equilateral triangle of edge L has area √3/4·L².
constexpr double kEquilateralAreaFactor = 0.4330127018922193;

}  // namespace

RemeshOptions membrane_remesh_options(const ProxyMesh& mesh, double bilayer_thickness, std::optional<double> edge) {
  RemeshOptions options;
  if (edge) {
    options.edge = *edge;
  } else {
    double area = 0.0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) area += world_area(mesh, t);
    const double edge_for_count = std::sqrt(area / (kEquilateralAreaFactor * double(kRemeshMaxTriangles)));
    options.edge = std::max(0.5 * bilayer_thickness, edge_for_count);
  }
  // Around creases, half the bilayer whatever the mesh's size: a large cell's coarser first pass would
  // round them over its own edge, not the bilayer's.
  options.crease_edge = edge ? options.edge : std::min(options.edge, 0.5 * bilayer_thickness);
  options.max_distance = std::max(bilayer_thickness, options.crease_edge) + 0.25 * options.crease_edge;
  options.max_edge = edge ? options.edge : kCoarsestEdgeFactor * options.edge;  // the scene's edge is kept everywhere
  options.crease_radius = std::max(kCreaseRadiusBilayers * bilayer_thickness, options.crease_edge);
  return options;
}

std::vector<double> triangle_creases(const ProxyMesh& mesh) {
  std::vector<glm::dvec3> normals(mesh.triangles.size(), glm::dvec3(0.0));
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::dvec3 p0 = mesh.corner_position(t, 0);
    const glm::dvec3 n = glm::cross(mesh.corner_position(t, 1) - p0, mesh.corner_position(t, 2) - p0);
    const double length = glm::length(n);
    if (length > 0.0) normals[t] = n / length;
  }
  std::vector<double> crease(mesh.triangles.size(), 0.0);
  for (const MeshEdge& e : collect_edges(mesh)) {
    if (e.uses.size() != 2) continue;
    const std::uint32_t a = e.uses[0].face, b = e.uses[1].face;
    if (normals[a] == glm::dvec3(0.0) || normals[b] == glm::dvec3(0.0)) continue;
    const double degrees = std::acos(std::clamp(glm::dot(normals[a], normals[b]), -1.0, 1.0)) * kDegreesPerRadian;
    crease[a] = std::max(crease[a], degrees);
    crease[b] = std::max(crease[b], degrees);
  }
  return crease;
}

double largest_crease_degrees(const ProxyMesh& mesh) {
  const std::vector<double> crease = triangle_creases(mesh);
  return crease.empty() ? 0.0 : *std::max_element(crease.begin(), crease.end());
}

std::optional<std::string> remesh_reason(const ProxyMesh& mesh) {
  const double crease = largest_crease_degrees(mesh);
  if (crease <= kRemeshCreaseDegrees) return std::nullopt;
  return number_text("neighbouring faces turn by up to %.1f°", crease) +
         number_text(" (a bilayer's shells follow at most %.0f°)", kRemeshCreaseDegrees);
}

nlohmann::json to_json(const RemeshReport& r) {
  return {{"reason", r.reason},
          {"triangles_in", r.triangles_in},
          {"triangles_out", r.triangles_out},
          {"triangles_at_uniform_edge", r.triangles_uniform},
          {"edge_A", r.edge},
          {"crease_edge_A", r.crease_edge},
          {"coarsest_edge_A", r.coarsest_edge},
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
                  std::to_string(r.triangles_out) + " triangles" + number_text(", edges %.1f", std::min(r.crease_edge, r.edge)) +
                  number_text("-%.1f Å", r.coarsest_edge) + " (" + std::to_string(r.triangles_uniform) +
                  number_text(" at %.1f Å everywhere)", r.edge);
  s += number_text("; creases %.1f°", r.largest_crease_in) + number_text(" -> %.1f°", r.largest_crease_out);
  s += number_text("; within %.1f Å", r.max_distance) + number_text(" of the input (bound %.1f Å)", r.distance_bound);
  s += number_text("; normals turned by up to %.1f°", r.largest_normal_deviation);
  if (r.area_in > 0.0) s += number_text("; area %+.2f %%", 100.0 * (r.area_out / r.area_in - 1.0));
  if (r.volume_in > 0.0) s += number_text(", volume %+.2f %%", 100.0 * (r.volume_out / r.volume_in - 1.0));
  return s;
}

}  // namespace nano::mesh
