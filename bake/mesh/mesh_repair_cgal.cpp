// CGAL's Polygon Mesh Processing repairs, in their own translation unit (template-heavy).
#include "bake/mesh/mesh_repair.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include "bake/mesh/vertex_normals.hpp"
#include "common/error.hpp"

namespace nano::mesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;
using Polygon = std::vector<std::size_t>;

// An undirected edge between two vertex indices, as one key.
std::uint64_t edge_key(std::size_t a, std::size_t b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
}
std::uint64_t directed_key(std::size_t a, std::size_t b) { return (std::uint64_t(a) << 32) | std::uint64_t(b); }

std::string vertex_text(const ProxyMesh& mesh, std::size_t v) {
  const glm::dvec3& p = mesh.positions[v];
  char text[160];
  std::snprintf(text, sizeof text, "vertex %zu (%.6g, %.6g, %.6g)", v, p.x, p.y, p.z);
  return text;
}

std::string list(const std::vector<std::size_t>& values) {
  std::string s;
  for (std::size_t k = 0; k < values.size(); ++k) s += (k ? ", " : "") + std::to_string(values[k]);
  return s;
}

// Three or more faces on one edge: refused with the first such edge (in face order) and the count.
void refuse_non_manifold_edges(const ProxyMesh& mesh, const std::vector<Polygon>& polygons,
                               const std::vector<std::size_t>& face_of, const InputSource& source) {
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> faces_on;
  for (std::size_t p = 0; p < polygons.size(); ++p)
    for (std::size_t k = 0; k < 3; ++k) faces_on[edge_key(polygons[p][k], polygons[p][(k + 1) % 3])].push_back(p);
  std::size_t count = 0;
  const std::vector<std::size_t>* first = nullptr;
  std::uint64_t first_key = 0;
  for (const auto& [key, faces] : faces_on) {
    if (faces.size() <= 2) continue;
    ++count;
    if (!first || faces.front() < first->front() || (faces.front() == first->front() && key < first_key))
      first = &faces, first_key = key;
  }
  if (count == 0) return;
  std::vector<std::size_t> triangles;
  for (std::size_t p : *first) triangles.push_back(face_of[p]);
  source.fail(
      "cannot repair: " + std::to_string(triangles.size()) + " faces (triangles " + list(triangles) +
      ") share the edge between " + vertex_text(mesh, first_key >> 32) + " and " +
      vertex_text(mesh, first_key & 0xffffffffu) + "; which of them belong together is the user's call" +
      (count > 1 ? " (" + std::to_string(count) + " such non-manifold edges; check-mesh names them all)" : std::string()));
}

// What orient_polygon_soup does, as it does it (the visitor is copied: it holds pointers).
struct OrientationRecord {
  std::vector<char> reversed;           // per polygon
  std::vector<std::size_t> origin;      // per point: the input vertex it copies (itself for input vertices)
  std::size_t vertices_split = 0, copies = 0;
};
struct OrientationVisitor : PMP::Default_orientation_visitor {
  OrientationRecord* record = nullptr;
  void non_manifold_vertex(std::size_t, std::size_t fans) {
    ++record->vertices_split;
    record->copies += fans - 1;
  }
  void polygon_orientation_reversed(std::size_t p) { record->reversed[p] ^= 1; }
  void duplicated_vertex(std::size_t v, std::size_t copy) {
    if (record->origin.size() <= copy) record->origin.resize(copy + 1);
    record->origin[copy] = record->origin[v];
  }
};

// After orientation, two faces walking an edge of the input the same way: a one-sided surface.
void refuse_one_sided(const ProxyMesh& mesh, const std::vector<Polygon>& polygons, const std::vector<std::size_t>& face_of,
                      const std::vector<std::size_t>& origin, const InputSource& source) {
  std::unordered_map<std::uint64_t, std::size_t> walked_by;
  for (std::size_t p = 0; p < polygons.size(); ++p)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t a = origin[polygons[p][k]], b = origin[polygons[p][(k + 1) % 3]];
      const auto [it, inserted] = walked_by.emplace(directed_key(a, b), p);
      if (!inserted)
        source.fail(
            "cannot repair: the faces cannot be oriented consistently (a one-sided surface, like a Möbius band): "
            "however they are turned, two faces walk an edge the same way, e.g. triangles " +
            std::to_string(std::min(face_of[it->second], face_of[p])) + " and " +
            std::to_string(std::max(face_of[it->second], face_of[p])) + " on the edge between " + vertex_text(mesh, a) +
            " and " + vertex_text(mesh, b));
    }
}

// Pieces of the soup (faces joined through shared edges), as a root face per face.
std::vector<std::size_t> soup_pieces(const std::vector<Polygon>& polygons) {
  std::vector<std::size_t> parent(polygons.size());
  std::iota(parent.begin(), parent.end(), std::size_t(0));
  const auto root = [&](std::size_t p) {
    while (parent[p] != p) p = parent[p] = parent[parent[p]];
    return p;
  };
  std::unordered_map<std::uint64_t, std::size_t> first_on;
  for (std::size_t p = 0; p < polygons.size(); ++p)
    for (std::size_t k = 0; k < 3; ++k) {
      const auto [it, inserted] = first_on.emplace(edge_key(polygons[p][k], polygons[p][(k + 1) % 3]), p);
      if (!inserted) parent[root(p)] = root(it->second);
    }
  for (std::size_t p = 0; p < polygons.size(); ++p) parent[p] = root(p);
  return parent;
}

// Of each piece, the faces orient_polygon_soup turned are made the minority: when it turned most
// of a piece, the piece is turned back, so that the faces said to be turned are those that
// disagreed with most of their piece (which way the piece faces is settled later, on the volume).
std::size_t keep_the_majority(std::vector<Polygon>& polygons, const std::vector<char>& reversed) {
  const std::vector<std::size_t> piece = soup_pieces(polygons);
  std::unordered_map<std::size_t, std::pair<std::size_t, std::size_t>> turned_of;  // piece -> (turned, faces)
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    auto& [turned, faces] = turned_of[piece[p]];
    turned += reversed[p] != 0, ++faces;
  }
  std::size_t turned_faces = 0;
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    const auto [turned, faces] = turned_of[piece[p]];
    if (2 * turned > faces) std::reverse(polygons[p].begin(), polygons[p].end());
  }
  for (const auto& [root, counts] : turned_of) turned_faces += std::min(counts.first, counts.second - counts.first);
  return turned_faces;
}

// The copies of a split vertex coincide, so the pieces would still touch there (a self-intersection
// to check-mesh): each copy moves towards the centre of its own fan's ring of neighbours by 1 % of
// its shortest edge. Returns the largest move.
double pull_copies_apart(std::vector<Kernel::Point_3>& points, const std::vector<Polygon>& polygons,
                         const std::vector<std::size_t>& origin, std::size_t input_vertices) {
  std::unordered_set<std::size_t> split;
  for (std::size_t v = input_vertices; v < points.size(); ++v) split.insert(v), split.insert(origin[v]);
  if (split.empty()) return 0.0;
  struct Ring {
    std::unordered_set<std::size_t> neighbours;
    double shortest = INFINITY;
  };
  std::unordered_map<std::size_t, Ring> rings;
  for (const Polygon& polygon : polygons)
    for (std::size_t k = 0; k < 3; ++k) {
      if (!split.count(polygon[k])) continue;
      Ring& ring = rings[polygon[k]];
      for (std::size_t other : {polygon[(k + 1) % 3], polygon[(k + 2) % 3]}) {
        ring.neighbours.insert(other);
        ring.shortest = std::min(ring.shortest, std::sqrt(CGAL::to_double(CGAL::squared_distance(points[polygon[k]], points[other]))));
      }
    }
  std::vector<std::pair<std::size_t, Kernel::Point_3>> moved;
  double largest = 0.0;
  for (const auto& [v, ring] : rings) {
    Kernel::Vector_3 centre(0, 0, 0);
    for (std::size_t w : ring.neighbours) centre = centre + (points[w] - CGAL::ORIGIN);
    const Kernel::Vector_3 towards = centre / double(ring.neighbours.size()) - (points[v] - CGAL::ORIGIN);
    const double length = std::sqrt(CGAL::to_double(towards.squared_length()));
    if (!(length > 0.0) || !std::isfinite(ring.shortest)) continue;
    const double step = 0.01 * ring.shortest;
    moved.emplace_back(v, points[v] + towards * (step / length));
    largest = std::max(largest, step);
  }
  for (const auto& [v, p] : moved) points[v] = p;
  return largest;
}

struct TriangleHash {
  std::size_t operator()(const std::array<std::uint32_t, 3>& t) const {
    return std::hash<std::uint64_t>()((std::uint64_t(t[0]) << 42) ^ (std::uint64_t(t[1]) << 21) ^ t[2]);
  }
};

// Each face's corners in order, to tell afterwards which faces an operation turned over.
std::vector<std::array<std::uint32_t, 3>> corners_of(const SurfaceMesh& sm) {
  std::vector<std::array<std::uint32_t, 3>> corners(sm.number_of_faces());
  for (SurfaceMesh::Face_index f : sm.faces()) {
    int k = 0;
    for (SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(sm.halfedge(f), sm))
      if (k < 3) corners[f.idx()][k++] = std::uint32_t(v.idx());
  }
  return corners;
}

}  // namespace

namespace {

// The input's triangles as a polygon soup, without faces that repeat a corner or another face.
struct Soup {
  std::vector<Kernel::Point_3> points;
  std::vector<Polygon> polygons;
  std::vector<std::size_t> face_of;  // the input triangle of each polygon
};

Soup distinct_faces(const ProxyMesh& mesh, RepairReport& report, const InputSource& source) {
  Soup soup;
  for (const glm::dvec3& p : mesh.positions) soup.points.emplace_back(p.x, p.y, p.z);
  std::unordered_set<std::array<std::uint32_t, 3>, TriangleHash> seen;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      ++report.repeated_vertex_faces_removed;
      continue;
    }
    std::array<std::uint32_t, 3> sorted = t;
    std::sort(sorted.begin(), sorted.end());
    if (!seen.insert(sorted).second) {
      ++report.duplicate_faces_removed;
      continue;
    }
    soup.polygons.push_back({t[0], t[1], t[2]});
    soup.face_of.push_back(f);
  }
  if (soup.polygons.empty()) source.fail("cannot repair: no face is left");
  return soup;
}

// Orientation and non-manifold vertices, on the soup: CGAL turns faces to agree across their edges
// and gives each fan of faces around a vertex its own copy of it.
void orient_and_split(const ProxyMesh& mesh, Soup& soup, RepairReport& report, const InputSource& source) {
  OrientationRecord record;
  record.reversed.assign(soup.polygons.size(), 0);
  record.origin.resize(soup.points.size());
  std::iota(record.origin.begin(), record.origin.end(), std::size_t(0));
  OrientationVisitor visitor;
  visitor.record = &record;
  const std::size_t input_vertices = soup.points.size();
  PMP::orient_polygon_soup(soup.points, soup.polygons, CGAL::parameters::visitor(visitor));
  refuse_one_sided(mesh, soup.polygons, soup.face_of, record.origin, source);
  report.non_manifold_vertices_split = record.vertices_split;
  report.vertex_copies_added = record.copies;
  report.faces_reoriented = keep_the_majority(soup.polygons, record.reversed);
  if (!PMP::is_polygon_soup_a_polygon_mesh(soup.polygons))
    source.fail("cannot repair: the faces do not form a surface even after orienting them and splitting "
                "their non-manifold vertices; check-mesh names the problems");
  report.split_separation = pull_copies_apart(soup.points, soup.polygons, record.origin, input_vertices);
}

// CGAL mends a zero-area face by flipping or collapsing edges: count the degenerate faces it left.
void remove_degenerate_faces(SurfaceMesh& sm, RepairReport& report) {
  const auto degenerate_faces = [&sm] {
    std::size_t n = 0;
    for (SurfaceMesh::Face_index f : sm.faces()) n += PMP::is_degenerate_triangle_face(f, sm);
    return n;
  };
  const std::size_t degenerate_before = degenerate_faces();
  if (degenerate_before > 0) PMP::remove_degenerate_faces(sm);
  sm.collect_garbage();
  report.degenerate_faces_removed = degenerate_before - std::min(degenerate_before, degenerate_faces());
}

void fill_small_holes(SurfaceMesh& sm, const RepairOptions& options, RepairReport& report) {
  std::vector<SurfaceMesh::Halfedge_index> cycles;
  PMP::extract_boundary_cycles(sm, std::back_inserter(cycles));
  for (SurfaceMesh::Halfedge_index h : cycles) {
    std::size_t edges = 0;
    for (SurfaceMesh::Halfedge_index e : CGAL::halfedges_around_face(h, sm)) (void)e, ++edges;
    if (edges > options.max_hole_edges) {
      ++report.holes_left;
      report.largest_hole_left = std::max(report.largest_hole_left, edges);
      continue;
    }
    std::vector<SurfaceMesh::Face_index> patch;
    PMP::triangulate_hole(sm, h, std::back_inserter(patch));
    if (patch.empty()) {
      ++report.holes_not_closed;
      continue;
    }
    ++report.holes_filled;
    report.triangles_added += patch.size();
  }
  sm.collect_garbage();
}

// Each closed piece faces out of the volume it bounds (a piece inside another into it).
void face_pieces_outward(SurfaceMesh& sm, RepairReport& report) {
  auto piece = sm.add_property_map<SurfaceMesh::Face_index, std::size_t>("f:piece", 0).first;
  report.pieces = PMP::connected_components(sm, piece);
  if (!CGAL::is_closed(sm)) return;
  const std::vector<std::array<std::uint32_t, 3>> before = corners_of(sm);
  PMP::orient_to_bound_a_volume(sm);
  const std::vector<std::array<std::uint32_t, 3>> after = corners_of(sm);
  std::unordered_set<std::size_t> turned;
  for (SurfaceMesh::Face_index f : sm.faces()) {
    const auto& a = before[f.idx()];
    const auto& b = after[f.idx()];
    const bool same = (b == a) || (b == std::array{a[1], a[2], a[0]}) || (b == std::array{a[2], a[0], a[1]});
    if (!same) turned.insert(piece[f]);
  }
  report.pieces_turned_over = turned.size();
  report.reoriented = !turned.empty();
}

ProxyMesh proxy_of(const SurfaceMesh& sm, const InputSource& source) {
  ProxyMesh repaired;
  for (SurfaceMesh::Vertex_index v : sm.vertices()) {
    const Kernel::Point_3& p = sm.point(v);
    repaired.positions.emplace_back(p.x(), p.y(), p.z());
  }
  for (SurfaceMesh::Face_index f : sm.faces()) {
    Triangle t{};
    int k = 0;
    for (SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      // Invariant, not input: every face handed to CGAL is a triangle and its repairs keep them so.
      if (k == 3) throw std::logic_error("repair_mesh: CGAL left a face of more than three vertices");
      t[k++] = std::uint32_t(v.idx());
    }
    repaired.triangles.push_back(t);
  }
  // Removing degenerate faces can take every face of a mesh made of slivers.
  if (repaired.triangles.empty()) source.fail("cannot repair: no face is left");
  compute_angle_weighted_normals(repaired);
  return repaired;
}

}  // namespace

RepairReport repair_mesh(ProxyMesh& mesh, const InputSource& source, const RepairOptions& options) {
  RepairReport report;
  report.faces_before = mesh.triangles.size();
  Soup soup = distinct_faces(mesh, report, source);
  refuse_non_manifold_edges(mesh, soup.polygons, soup.face_of, source);
  orient_and_split(mesh, soup, report, source);
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(soup.points, soup.polygons, sm);
  remove_degenerate_faces(sm, report);
  fill_small_holes(sm, options, report);
  face_pieces_outward(sm, report);
  mesh = proxy_of(sm, source);
  report.faces_after = mesh.triangles.size();
  return report;
}

nlohmann::json to_json(const RepairReport& r) {
  return {{"faces_before", r.faces_before},
          {"faces_after", r.faces_after},
          {"repeated_vertex_faces_removed", r.repeated_vertex_faces_removed},
          {"duplicate_faces_removed", r.duplicate_faces_removed},
          {"non_manifold_vertices_split", r.non_manifold_vertices_split},
          {"vertex_copies_added", r.vertex_copies_added},
          {"split_separation", r.split_separation},
          {"faces_reoriented", r.faces_reoriented},
          {"degenerate_faces_removed", r.degenerate_faces_removed},
          {"holes_filled", r.holes_filled},
          {"triangles_added", r.triangles_added},
          {"holes_left", r.holes_left},
          {"largest_hole_left", r.largest_hole_left},
          {"holes_not_closed", r.holes_not_closed},
          {"pieces_turned_over", r.pieces_turned_over},
          {"reoriented", r.reoriented},
          {"pieces", r.pieces},
          {"changed", r.changed()}};
}

std::string describe(const RepairReport& r) {
  const std::string pieces =
      r.pieces > 1 ? std::to_string(r.pieces) + " separate pieces" : std::string();
  if (!r.changed() && r.holes_left == 0 && r.holes_not_closed == 0)
    return pieces.empty() ? "repair: nothing to mend" : "repair: nothing to mend (the mesh is " + pieces + ")";
  std::string s = "repair: " + std::to_string(r.faces_before) + " -> " + std::to_string(r.faces_after) + " faces";
  if (!r.changed()) s += "; nothing mended";
  if (r.repeated_vertex_faces_removed) s += "; " + std::to_string(r.repeated_vertex_faces_removed) + " faces with a repeated vertex dropped";
  if (r.duplicate_faces_removed) s += "; " + std::to_string(r.duplicate_faces_removed) + " duplicate faces dropped";
  if (r.non_manifold_vertices_split) {
    char separation[64];
    std::snprintf(separation, sizeof separation, "%.3g", r.split_separation);
    s += "; " + std::to_string(r.non_manifold_vertices_split) + " non-manifold vertices split (" +
         std::to_string(r.vertex_copies_added) + " copies added, pulled at most " + separation + " into their own fans)";
  }
  if (r.faces_reoriented) s += "; " + std::to_string(r.faces_reoriented) + " faces turned to agree with their neighbours";
  if (r.degenerate_faces_removed) s += "; " + std::to_string(r.degenerate_faces_removed) + " degenerate faces mended (edges flipped or collapsed)";
  if (r.holes_filled)
    s += "; " + std::to_string(r.holes_filled) + " holes closed with " + std::to_string(r.triangles_added) + " triangles";
  if (r.holes_left)
    s += "; " + std::to_string(r.holes_left) + " holes too large to close (the largest has " +
         std::to_string(r.largest_hole_left) + " border edges)";
  if (r.holes_not_closed) s += "; " + std::to_string(r.holes_not_closed) + " holes CGAL found no triangulation for";
  if (r.reoriented)
    s += r.pieces <= 1 ? std::string("; turned outward")
                       : "; " + std::to_string(r.pieces_turned_over) + " pieces turned over to bound a volume";
  if (!pieces.empty()) s += "; the result is " + pieces;
  return s;
}

}  // namespace nano::mesh
