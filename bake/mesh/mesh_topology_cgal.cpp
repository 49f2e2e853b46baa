// The only translation unit that includes CGAL (see mesh_topology_cgal.hpp).
#include "bake/mesh/mesh_topology_cgal.hpp"

#include <cmath>
#include <iterator>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

namespace nano::mesh {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point3>;
namespace PMP = CGAL::Polygon_mesh_processing;

Point3 to_cgal(const glm::dvec3& p) { return {p.x, p.y, p.z}; }
}  // namespace

SolidProperties analyse_solid(const ProxyMesh& mesh, bool check_intersections) {
  SolidProperties result;
  std::vector<Point3> points;
  points.reserve(mesh.positions.size());
  for (const glm::dvec3& p : mesh.positions) points.push_back(to_cgal(p));
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(mesh.triangles.size());
  for (const Triangle& t : mesh.triangles) polygons.push_back({t[0], t[1], t[2]});

  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) return result;
  result.polygon_mesh = true;
  SurfaceMesh surface;
  // Faces are added in soup order, so Surface_mesh face i is triangle i.
  PMP::polygon_soup_to_polygon_mesh(points, polygons, surface);
  result.area = CGAL::to_double(PMP::area(surface));
  result.closed = CGAL::is_closed(surface);
  if (!result.closed) return result;
  result.volume = CGAL::to_double(PMP::volume(surface));
  result.outward = PMP::is_outward_oriented(surface);
  if (check_intersections) {
    std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> pairs;
    PMP::self_intersections(surface, std::back_inserter(pairs));
    for (const auto& [f, g] : pairs)
      result.self_intersections.emplace_back(static_cast<std::uint32_t>(f.idx()), static_cast<std::uint32_t>(g.idx()));
  }
  return result;
}

std::vector<double> distances_along_normals(const ProxyMesh& mesh, bool inward) {
  using Triangle3 = Kernel::Triangle_3;
  using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle3>::const_iterator>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
  std::vector<Triangle3> triangles;
  triangles.reserve(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    triangles.emplace_back(to_cgal(mesh.corner_position(t, 0)), to_cgal(mesh.corner_position(t, 1)),
                           to_cgal(mesh.corner_position(t, 2)));
  std::vector<double> distances(triangles.size(), 0.0);
  if (triangles.empty()) return distances;
  const Tree tree(triangles.begin(), triangles.end());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (triangles[t].is_degenerate()) continue;
    const Kernel::Vector_3 n = triangles[t].supporting_plane().orthogonal_vector();
    const Point3 centre = CGAL::centroid(triangles[t]);
    const Kernel::Ray_3 ray(centre, inward ? -n : n);
    // Its neighbours (sharing a corner) are not the other side: a ray from a long thin triangle's
    // centroid can graze the next one at once, a fold the creases measure, not a wall.
    const Triangle& own = mesh.triangles[t];
    const auto neighbour = [&](std::vector<Triangle3>::const_iterator id) {
      const Triangle& other = mesh.triangles[std::size_t(id - triangles.begin())];
      for (const std::uint32_t a : own)
        for (const std::uint32_t b : other)
          if (a == b) return true;
      return false;
    };
    const auto hit = tree.first_intersection(ray, neighbour);
    distances[t] = INFINITY;
    if (!hit) continue;
    if (const Point3* p = boost::get<Point3>(&hit->first)) distances[t] = std::sqrt(CGAL::squared_distance(centre, *p));
    else if (const Kernel::Segment_3* s = boost::get<Kernel::Segment_3>(&hit->first))
      distances[t] = std::sqrt(std::min(CGAL::squared_distance(centre, s->source()), CGAL::squared_distance(centre, s->target())));
  }
  return distances;
}

}  // namespace nano::mesh
