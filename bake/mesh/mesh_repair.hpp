#pragma once
// "repair": true in a scene's mesh: what CGAL's Polygon Mesh Processing can mend without guessing
// at the user's shape — degenerate (zero-area) faces removed by collapsing them into their
// neighbours, holes of up to max_hole_edges border edges closed by a minimal-area triangulation,
// a closed mesh turned outward — and an account of every change. No CGAL type crosses this header.
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

struct RepairOptions {
  std::size_t max_hole_edges = 64;  // larger holes are left (and reported): they are the shape
};

struct RepairReport {
  std::size_t faces_before = 0, faces_after = 0;
  std::size_t repeated_vertex_faces_removed = 0;  // faces naming one vertex twice, dropped from the soup
  std::size_t degenerate_faces_removed = 0;       // zero-area faces CGAL mended (edges flipped or collapsed)
  std::size_t holes_filled = 0, triangles_added = 0;
  std::size_t holes_left = 0;                      // more than max_hole_edges border edges
  bool reoriented = false;                         // the closed mesh was inside out
  bool changed() const {
    return repeated_vertex_faces_removed || degenerate_faces_removed || holes_filled || reoriented;
  }
};

// Repairs `mesh` in place. Its UVs and normals are dropped (the faces change; the baker makes
// charts and normals again). Throws std::invalid_argument when the faces do not form a polygon
// mesh CGAL can mend (non-manifold edges or vertices: which faces belong together is the user's call).
RepairReport repair_mesh(ProxyMesh& mesh, const RepairOptions& options = {});

nlohmann::json to_json(const RepairReport& report);
std::string describe(const RepairReport& report);

}  // namespace nano::mesh
