#pragma once
// "repair": true in a scene's mesh: what CGAL's Polygon Mesh Processing can mend without guessing
// at the user's shape, and an account of every change:
// - faces naming a vertex twice dropped; a face listed twice (in either winding) kept once;
// - non-manifold vertices (where two or more fans of faces meet at one point) split, one vertex per
//   fan (CGAL's orient_polygon_soup), the copies then pulled apart into their own fans by 1 % of
//   their shortest edge, so that the pieces no longer touch;
// - faces oriented against their neighbours turned to agree with them (orient_polygon_soup; of each
//   piece, the faces that disagree with the majority of its faces);
// - degenerate (zero-area) faces removed by collapsing them into their neighbours;
// - holes of up to max_hole_edges border edges closed by a minimal-area triangulation;
// - a closed mesh turned to bound a volume: each piece outward, a piece inside another inward.
// Non-manifold edges (three or more faces on an edge) and one-sided surfaces (a Möbius band) are
// refused: which faces belong together is the user's call. No CGAL type crosses this header.
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bake/mesh/proxy_mesh.hpp"
#include "common/error.hpp"

namespace nano::mesh {

struct RepairOptions {
  std::size_t max_hole_edges = 64;  // larger holes are left (and reported): they are the shape
};

struct RepairReport {
  std::size_t faces_before = 0, faces_after = 0;
  std::size_t repeated_vertex_faces_removed = 0;  // faces naming one vertex twice, dropped from the soup
  std::size_t duplicate_faces_removed = 0;        // a face on the same vertices as an earlier one (either winding)
  std::size_t non_manifold_vertices_split = 0;    // vertices where several fans of faces met
  std::size_t vertex_copies_added = 0;            // one per fan beyond the first
  double split_separation = 0.0;                  // how far the copies were pulled apart (largest move)
  std::size_t faces_reoriented = 0;               // turned to agree with their neighbours
  std::size_t degenerate_faces_removed = 0;       // zero-area faces CGAL mended (edges flipped or collapsed)
  std::size_t holes_filled = 0, triangles_added = 0;
  std::size_t holes_left = 0;                      // more than max_hole_edges border edges
  std::size_t largest_hole_left = 0;               // its border edges
  std::size_t holes_not_closed = 0;                // small enough, but CGAL's triangulate_hole found no patch
  std::size_t pieces_turned_over = 0;              // closed pieces turned to bound a volume (inside out before)
  bool reoriented = false;                         // pieces_turned_over > 0
  std::size_t pieces = 0;                          // connected pieces of the result
  bool changed() const {
    return repeated_vertex_faces_removed || duplicate_faces_removed || non_manifold_vertices_split ||
           faces_reoriented || degenerate_faces_removed || holes_filled || reoriented;
  }
};

// Repairs `mesh` in place. Its UVs and normals are dropped (the faces change; the baker makes
// charts and normals again). Vertices keep their indices, copies made by a split after them,
// unless collapsing a degenerate face removed one.
// Throws an InputError from `source` (the mesh file, and the compartment the scene reads it for)
// naming the vertices and triangles (0-based, as check-mesh names them) where the faces do not
// form a surface CGAL can mend: a non-manifold edge, a one-sided surface, no face left.
RepairReport repair_mesh(ProxyMesh& mesh, const InputSource& source, const RepairOptions& options = {});

nlohmann::json to_json(const RepairReport& report);
std::string describe(const RepairReport& report);

}  // namespace nano::mesh
