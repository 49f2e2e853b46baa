// The only translation unit that instantiates CGAL's parameterizers (template-heavy: kept apart
// from mesh_topology_cgal.cpp so either compiles alone).
#include "bake/mesh/chart_parameterization.hpp"

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Circular_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Mean_value_coordinates_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

namespace nano::mesh {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;
namespace SMP = CGAL::Surface_mesh_parameterization;

template <class Parameterizer>
std::optional<std::vector<glm::dvec2>> run(SurfaceMesh& sm, const std::vector<VertexIndex>& vertices) {
  const auto border = CGAL::Polygon_mesh_processing::longest_border(sm).first;
  if (border == SurfaceMesh::null_halfedge()) return std::nullopt;
  auto [uv_map, created] = sm.add_property_map<VertexIndex, Kernel::Point_2>("v:uv");
  if (SMP::parameterize(sm, Parameterizer(), border, uv_map) != SMP::OK) return std::nullopt;
  std::vector<glm::dvec2> uvs;
  uvs.reserve(vertices.size());
  for (VertexIndex v : vertices) uvs.emplace_back(uv_map[v].x(), uv_map[v].y());
  return uvs;
}

}  // namespace

const char* to_string(ChartMethod method) {
  return method == ChartMethod::lscm ? "LSCM" : "mean-value coordinates, circular border";
}

std::optional<std::vector<glm::dvec2>> parameterize_chart(const std::vector<glm::dvec3>& positions,
                                                          const std::vector<Triangle>& triangles, ChartMethod method) {
  SurfaceMesh sm;
  std::vector<VertexIndex> vertices;
  vertices.reserve(positions.size());
  for (const glm::dvec3& p : positions) vertices.push_back(sm.add_vertex(Kernel::Point_3(p.x, p.y, p.z)));
  for (const Triangle& t : triangles)
    if (sm.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]) == SurfaceMesh::null_face()) return std::nullopt;
  if (method == ChartMethod::lscm) return run<SMP::LSCM_parameterizer_3<SurfaceMesh>>(sm, vertices);
  return run<SMP::Mean_value_coordinates_parameterizer_3<SurfaceMesh, SMP::Circular_border_arc_length_parameterizer_3<SurfaceMesh>>>(
      sm, vertices);
}

}  // namespace nano::mesh
