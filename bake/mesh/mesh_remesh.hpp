#pragma once
// Prepares a user's closed, manifold, outward mesh for shelling: a membrane is a rigid bilayer laid
// along the surface's normals, so a crease sharper than the bilayer can follow, or triangles coarse
// against the surface's curvature, leave molecules no prism that contains them. The baker remeshes
// such a mesh itself — isotropic remeshing (CGAL Polygon Mesh Processing) to an edge derived from the
// membrane, smoothing that rounds creases while every vertex is held within a stated distance of the
// user's surface, coarser triangles where the surface is flat enough — and reports what it changed. No CGAL type crosses this header.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bake/mesh/proxy_mesh.hpp"
#include "common/error.hpp"

namespace nano::mesh {

// Creases the shells take without remeshing: neighbouring faces' normals at most this far apart.
inline constexpr double kRemeshCreaseDegrees = 20.0;
// The first, uniform remeshing pass makes at most this many triangles (the edge grows instead;
// creases get finer ones after it, flat parts coarser).
inline constexpr std::size_t kRemeshMaxTriangles = 150000;
// Creases are rounded over this many bilayer thicknesses.
inline constexpr double kCreaseRadiusBilayers = 1.5;

// Where the surface is flat, triangles grow up to this many times the edge.
inline constexpr double kCoarsestEdgeFactor = 16.0;

struct RemeshOptions {
  double edge = 0.0;          // target edge length, Å (> 0)
  double max_distance = 0.0;  // Å: the remeshed surface (vertices, edge midpoints, centroids) stays this close to the input (> 0)
  double crease_radius = 0.0; // Å: creases are rounded over about this radius (0: not smoothed)
  double max_edge = 0.0;      // Å: flat enough regions are coarsened up to this edge (<= edge: uniform)
  double crease_edge = 0.0;   // Å: the edge around creases, when finer than `edge` (0: `edge`)
};

// The options the baker derives for a membrane `bilayer_thickness` Å thick on `mesh`: creases rounded
// over one thickness (so the bilayer's inner leaflet, half a thickness deep, never meets itself
// inside a convex crease, nor the outer one outside a concave crease), an edge of half the thickness
// around the creases, grown elsewhere so that the first pass stays under kRemeshMaxTriangles, and a
// distance bound of one thickness (or
// one edge, if larger) plus a quarter edge: a chord across a rounded crease lies farther from the input
// than its vertices, which are held half an edge inside the bound.
// `edge`: the scene's own edge instead of the derived one (the bound and radius follow it).
RemeshOptions membrane_remesh_options(const ProxyMesh& mesh, double bilayer_thickness,
                                      std::optional<double> edge = std::nullopt);

// Per triangle, the largest angle (degrees) between its normal and a neighbour's across one of its
// edges; 0 without interior edges. Degenerate faces are skipped.
std::vector<double> triangle_creases(const ProxyMesh& mesh);
// The largest of them over the mesh.
double largest_crease_degrees(const ProxyMesh& mesh);

// Why a mesh needs remeshing for a membrane, or nothing: creases above kRemeshCreaseDegrees.
std::optional<std::string> remesh_reason(const ProxyMesh& mesh);

struct RemeshReport {
  std::string reason;                      // why the baker remeshed (the scene's edge, or a crease)
  std::size_t triangles_in = 0, triangles_out = 0;
  std::size_t triangles_uniform = 0;       // after the first, uniform pass at `edge` (what a uniform edge would give)
  double edge = 0.0;                       // target edge, Å
  double crease_edge = 0.0;                // Å: around creases (`edge`, or half the bilayer when finer)
  double coarsest_edge = 0.0;              // Å: where the surface is flattest
  double distance_bound = 0.0;             // Å
  double largest_crease_in = 0.0;          // degrees between neighbouring faces
  double largest_crease_out = 0.0;
  double largest_normal_deviation = 0.0;   // degrees: a remeshed face against the input face nearest it
  double max_distance = 0.0;               // Å: remeshed vertices, edge midpoints and centroids to the input
  double area_in = 0.0, area_out = 0.0;    // Å²
  double volume_in = 0.0, volume_out = 0.0;  // Å³
  int smoothing_steps = 0;
};

// Remeshes `mesh` (closed, manifold, outward) in place: isotropic remeshing to options.edge, then
// umbrella (Laplacian) smoothing of the vertices within crease_radius of an edge sharper than
// kRemeshCreaseDegrees — 2·(crease_radius / edge)² steps, a diffusion over about that radius — every
// vertex pulled back to within options.max_distance of the input surface after each step and the
// smoothed faces remeshed every two; then, level by level, the faces whose corners' surroundings
// turn by less than 0.14 rad per edge remeshed at twice the edge, up to options.max_edge, the
// borders between levels rounded again, and faces with an angle under 5° remeshed with their
// surroundings.
// UVs are dropped (the baker makes charts for the new surface) and normals recomputed. Throws an InputError from
// `source` (the mesh file, and the compartment) when the triangles do not form a closed polygon mesh, and
// std::invalid_argument when the options are not positive (a caller's bug: whoever reads them refuses those).
RemeshReport remesh_for_membrane(ProxyMesh& mesh, const RemeshOptions& options, const std::string& reason,
                                 const InputSource& source);

nlohmann::json to_json(const RemeshReport& report);
std::string describe(const RemeshReport& report);

}  // namespace nano::mesh
