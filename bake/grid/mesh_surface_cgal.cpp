// The only translation unit of nano_grid that includes CGAL (see mesh_surface.hpp).
#include "bake/grid/mesh_surface.hpp"

#include <algorithm>
#include <iterator>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include "common/error.hpp"

namespace nano::grid {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point3>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using SideOf = CGAL::Side_of_triangle_mesh<SurfaceMesh, Kernel, CGAL::Default, Tree>;
namespace PMP = CGAL::Polygon_mesh_processing;

Point3 to_cgal(const glm::dvec3& p) { return {p.x, p.y, p.z}; }
}  // namespace

struct MeshSurface::Impl {
  mesh::ProxyMesh mesh;
  SurfaceMesh surface;
  Tree tree;
  std::unique_ptr<SideOf> side;
};

MeshSurface::MeshSurface(const mesh::ProxyMesh& mesh, const std::string& context) : impl_(std::make_unique<Impl>()) {
  if (mesh.triangles.empty()) throw InputError(context, "mesh", "the mesh has no triangles");
  std::vector<Point3> points;
  points.reserve(mesh.positions.size());
  for (const glm::dvec3& p : mesh.positions) points.push_back(to_cgal(p));
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(mesh.triangles.size());
  for (const mesh::Triangle& t : mesh.triangles) {
    for (std::uint32_t v : t)
      if (v >= mesh.positions.size()) throw InputError(context, "mesh", "triangle index out of range");
    polygons.push_back({t[0], t[1], t[2]});
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons))
    throw InputError(context, "mesh", "the mesh is not a 2-manifold polygon mesh");
  // Faces are added in soup order, so Surface_mesh face i is triangle i.
  PMP::polygon_soup_to_polygon_mesh(points, polygons, impl_->surface);
  if (!CGAL::is_closed(impl_->surface))
    throw InputError(context, "mesh", "the mesh is not closed: inside and outside are undefined");
  impl_->mesh.positions = mesh.positions;
  impl_->mesh.triangles = mesh.triangles;
  impl_->tree.insert(faces(impl_->surface).first, faces(impl_->surface).second, impl_->surface);
  // Build everything now: lazy construction on the first query would race between threads.
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
  (void)impl_->tree.squared_distance(to_cgal(mesh.positions[mesh.triangles[0][0]]));
  impl_->side = std::make_unique<SideOf>(impl_->tree);
}

MeshSurface::~MeshSurface() = default;

const mesh::ProxyMesh& MeshSurface::mesh() const { return impl_->mesh; }

bool MeshSurface::contains(const glm::dvec3& p) const {
  return (*impl_->side)(to_cgal(p)) == CGAL::ON_BOUNDED_SIDE;
}

double MeshSurface::squared_distance(const glm::dvec3& p) const {
  return impl_->tree.squared_distance(to_cgal(p));
}

std::vector<std::uint32_t> MeshSurface::triangles_meeting(const glm::dvec3& lo, const glm::dvec3& hi) const {
  std::vector<Primitive::Id> hits;
  impl_->tree.all_intersected_primitives(CGAL::Bbox_3(lo.x, lo.y, lo.z, hi.x, hi.y, hi.z), std::back_inserter(hits));
  std::vector<std::uint32_t> ids;
  ids.reserve(hits.size());
  for (const auto& f : hits) ids.push_back(static_cast<std::uint32_t>(f.idx()));
  std::sort(ids.begin(), ids.end());
  return ids;
}

}  // namespace nano::grid
