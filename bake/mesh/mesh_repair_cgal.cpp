// CGAL's Polygon Mesh Processing repairs, in their own translation unit (template-heavy).
#include "bake/mesh/mesh_repair.hpp"

#include <algorithm>
#include <stdexcept>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include "bake/mesh/vertex_normals.hpp"

namespace nano::mesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

}  // namespace

RepairReport repair_mesh(ProxyMesh& mesh, const RepairOptions& options) {
  RepairReport report;
  report.faces_before = mesh.triangles.size();
  std::vector<Kernel::Point_3> points;
  for (const glm::dvec3& p : mesh.positions) points.emplace_back(p.x, p.y, p.z);
  std::vector<std::vector<std::size_t>> polygons;
  for (const Triangle& t : mesh.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      ++report.repeated_vertex_faces_removed;
      continue;
    }
    polygons.push_back({t[0], t[1], t[2]});
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons))
    throw std::invalid_argument(
        "cannot repair: the faces do not form an oriented 2-manifold (non-manifold edges or vertices, or faces "
        "oriented against each other); check-mesh names them");
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  // CGAL mends a zero-area face by flipping or collapsing edges: count the degenerate faces it left.
  const auto degenerate_faces = [&sm] {
    std::size_t n = 0;
    for (SurfaceMesh::Face_index f : sm.faces()) n += PMP::is_degenerate_triangle_face(f, sm);
    return n;
  };
  const std::size_t degenerate_before = degenerate_faces();
  if (degenerate_before > 0) PMP::remove_degenerate_faces(sm);
  sm.collect_garbage();
  report.degenerate_faces_removed = degenerate_before - std::min(degenerate_before, degenerate_faces());

  std::vector<SurfaceMesh::Halfedge_index> cycles;
  PMP::extract_boundary_cycles(sm, std::back_inserter(cycles));
  for (SurfaceMesh::Halfedge_index h : cycles) {
    std::size_t edges = 0;
    for (SurfaceMesh::Halfedge_index e : CGAL::halfedges_around_face(h, sm)) (void)e, ++edges;
    if (edges > options.max_hole_edges) {
      ++report.holes_left;
      continue;
    }
    std::vector<SurfaceMesh::Face_index> patch;
    PMP::triangulate_hole(sm, h, std::back_inserter(patch));
    if (patch.empty()) {
      ++report.holes_left;
      continue;
    }
    ++report.holes_filled;
    report.triangles_added += patch.size();
  }
  if (CGAL::is_closed(sm) && !PMP::is_outward_oriented(sm)) {
    PMP::reverse_face_orientations(sm);
    report.reoriented = true;
  }
  sm.collect_garbage();

  ProxyMesh repaired;
  for (SurfaceMesh::Vertex_index v : sm.vertices()) {
    const Kernel::Point_3& p = sm.point(v);
    repaired.positions.emplace_back(p.x(), p.y(), p.z());
  }
  for (SurfaceMesh::Face_index f : sm.faces()) {
    Triangle t{};
    int k = 0;
    for (SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (k == 3) throw std::invalid_argument("cannot repair: CGAL left a face of more than three vertices");
      t[k++] = std::uint32_t(v.idx());
    }
    repaired.triangles.push_back(t);
  }
  if (repaired.triangles.empty()) throw std::invalid_argument("cannot repair: no face is left");
  compute_angle_weighted_normals(repaired);
  report.faces_after = repaired.triangles.size();
  mesh = std::move(repaired);
  return report;
}

nlohmann::json to_json(const RepairReport& r) {
  return {{"faces_before", r.faces_before},
          {"faces_after", r.faces_after},
          {"repeated_vertex_faces_removed", r.repeated_vertex_faces_removed},
          {"degenerate_faces_removed", r.degenerate_faces_removed},
          {"holes_filled", r.holes_filled},
          {"triangles_added", r.triangles_added},
          {"holes_left", r.holes_left},
          {"reoriented", r.reoriented}};
}

std::string describe(const RepairReport& r) {
  if (!r.changed() && r.holes_left == 0) return "repair: nothing to mend";
  std::string s = "repair: " + std::to_string(r.faces_before) + " -> " + std::to_string(r.faces_after) + " faces";
  if (r.repeated_vertex_faces_removed) s += "; " + std::to_string(r.repeated_vertex_faces_removed) + " faces with a repeated vertex dropped";
  if (r.degenerate_faces_removed) s += "; " + std::to_string(r.degenerate_faces_removed) + " degenerate faces mended (edges flipped or collapsed)";
  if (r.holes_filled)
    s += "; " + std::to_string(r.holes_filled) + " holes closed with " + std::to_string(r.triangles_added) + " triangles";
  if (r.holes_left) s += "; " + std::to_string(r.holes_left) + " holes too large to close";
  if (r.reoriented) s += "; turned outward";
  return s;
}

}  // namespace nano::mesh
