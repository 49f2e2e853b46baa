#pragma once
// check-mesh: is this proxy mesh usable for the shell (prisms over triangles, Wang tiles mapped
// through the UV chart)? Collects EVERY problem with its face index, rule and magnitude, plus the
// numbers the later bake stages need (global UV scale k, replication area W×H, distortion).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

// Rule names as they appear in reports; tests and scripts match on them.
namespace rule {
inline constexpr const char* border_edge = "border edge";                          // value: edge length
inline constexpr const char* holes = "holes";                                      // value: boundary loops
inline constexpr const char* too_many_triangles = "too many triangles";            // value: triangles
inline constexpr const char* non_manifold_edge = "non-manifold edge";              // value: faces on the edge
inline constexpr const char* non_manifold_vertex = "non-manifold vertex";          // value: separate fans
inline constexpr const char* inconsistent_orientation = "inconsistent orientation";  // value: neighbour face
inline constexpr const char* inward_orientation = "inward orientation";            // value: signed volume
inline constexpr const char* not_polygon_mesh = "not a polygon mesh";              // CGAL refused the soup
inline constexpr const char* repeated_vertex = "degenerate triangle (repeated vertex)";
inline constexpr const char* zero_area = "degenerate triangle (zero area)";       // value: area
inline constexpr const char* sliver = "sliver triangle";                           // value: min angle (deg)
inline constexpr const char* self_intersection = "self-intersection";             // value: other face
inline constexpr const char* no_uvs = "no UVs";
inline constexpr const char* uv_outside = "UV outside [0,1]";                      // value: max distance outside
inline constexpr const char* zero_area_uv = "zero-area UV triangle";              // value: UV area
inline constexpr const char* flipped_uv = "flipped UV triangle";                   // value: signed UV area
inline constexpr const char* thin_uv = "long thin UV triangle inflates replication area";  // warning; value: elongation
}  // namespace rule

// The rules about UVs (no UVs, outside the square, zero-area, flipped): those the baker's charts
// (uv_charts.hpp) replace.
bool is_uv_rule(const std::string& rule);

struct MeshProblem {
  std::int64_t face = -1;  // 0-based triangle index; −1 for a whole-mesh problem
  std::string rule;
  double value = 0.0;
  std::string detail;
};

struct TriangleDistortion {
  std::uint32_t face = 0;
  double sigma1 = 0.0, sigma2 = 0.0;  // singular values of J / k, σ1 ≥ σ2
};

struct CheckOptions {
  // World size S of a Wang tile. Default: k / 20, i.e. 20 tiles across the unit UV square.
  std::optional<double> tile_size;
  double min_angle_degrees = 1.0;   // sliver rule
  std::size_t max_triangles = 4'000'000;  // a proxy mesh is low-poly: more is refused
  double thin_uv_elongation = 8.0;  // warning rule, see check_mesh
  std::size_t worst_count = 5;
};

struct MeshReport {
  std::size_t triangles = 0, vertices = 0;
  bool closed = false, manifold = false, oriented = false, outward = false;
  std::size_t holes = 0;              // boundary loops (connected runs of border edges)
  std::vector<MeshProblem> problems;  // any entry makes the mesh unusable
  std::vector<MeshProblem> warnings;  // usable, but worth knowing
  double area = 0.0;
  std::optional<double> volume;       // closed meshes only

  bool has_uvs = false;  // everything below needs UVs
  std::size_t seam_edges = 0;
  double seam_length = 0.0;
  std::size_t uv_charts = 0, mirrored_triangles = 0;
  double uv_scale_k = 0.0;
  double tile_size_world = 0.0, tile_size_uv = 0.0;
  std::array<int, 2> replication_area{0, 0};
  double sigma_min = 0.0, sigma_max = 0.0;
  std::vector<TriangleDistortion> worst;  // largest max(σ1, 1/σ2) first

  bool usable() const { return problems.empty(); }
};

// Rules, in the order they are reported:
// - size: more than max_triangles triangles;
// - topology (exact, from position indices): border edges, and the holes they bound (connected runs
//   of border edges, one whole-mesh problem with their count), non-manifold edges (> 2 faces) and
//   vertices (> 1 fan), inconsistent orientation (an interior edge walked the same way by both
//   faces); outward = CGAL's is_outward_oriented and a positive signed volume;
// - degenerate triangles: a repeated vertex index, or three exactly collinear corners (exact
//   predicate); slivers: smallest interior angle below min_angle_degrees (this also bounds the
//   aspect ratio: a triangle with all angles ≥ α has longest/shortest edge ≤ 1/sin α);
// - self-intersections (CGAL, closed meshes without degenerate triangles only);
// - UVs: present, inside [0,1]², UV triangle of zero area (exact orient2d), flipped: the exact
//   UV orientation is opposite to the area-weighted majority of its UV chart (faces joined across
//   non-seam edges). A whole chart mirrored relative to the surface is legal — the tile mapper
//   flips the bitangent — and only counted in mirrored_triangles; a fold inside a chart is not.
// - warning: a UV triangle whose box sets W or H of the replication area while its elongation
//   (longest box side)² / (2·UV area) exceeds thin_uv_elongation (1 for a right isosceles triangle).
MeshReport check_mesh(const ProxyMesh& mesh, const CheckOptions& options);
// The surface alone (every rule above but the UVs'; has_uvs and what follows it left unset): what
// the membrane fit judges before any chart is made.
MeshReport check_mesh_surface(const ProxyMesh& mesh, const CheckOptions& options);

nlohmann::json report_to_json(const MeshReport& report);
// Human-readable report; problem lines read "FILE:face N: RULE (value ...)".
std::string report_to_text(const MeshReport& report, const std::string& file);

}  // namespace nano::mesh
