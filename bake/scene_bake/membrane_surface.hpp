#pragma once
// How a membrane's tiles meet the meshes that wear it. A Wang set is collision-free in flat tile
// space; on a mesh the chart stretches it and the normals turn and tilt. Either the tiles are packed
// rigid (as dense as the lipid patch) and every copy is checked where it really stands
// (shell/membrane_pruning.hpp), or, for a membrane of more copies than that check affords, they are
// packed to survive what the meshes do to them and only the copies where that is not enough are
// checked: along UV seams and on the triangles that distort more than a tile set can be packed for
// (kPackableDistortion: a rounded crease, a knot's tight tube, a chart stretched at its rim). One
// such triangle never makes the whole set sparse, nor its packing endless.
#include <cstdint>
#include <span>
#include <vector>

#include "bake/mesh/proxy_mesh.hpp"
#include "bake/tiles/collision_shape.hpp"

namespace nano::scene_bake {

// What one triangle does to the tiles laid on it.
struct TriangleDistortion {
  double major = 0.0, minor = 0.0;  // the chart's singular values, Å of surface per UV unit (0: no usable chart)
  double turn_rate = 0.0;           // rad per Å (mesh::triangle_turn_rate)
  double tilt = 0.0;                // mesh::triangle_smooth_normal_tilt at the membrane's smoothness
  double sag = 0.0;                 // Å (mesh::triangle_facet_sag)
  double area = 0.0;                // Å²
};

std::vector<TriangleDistortion> triangle_distortions(const mesh::ProxyMesh& mesh, double smooth, int threads);

// The most a tile set is packed to survive. Beyond it the packing thins the bilayer: a POPC/POPE
// patch with the virion's proteins keeps 33 % of its rigid density at a stretch of 1.3 and a turn of
// 4·10⁻⁴ rad/Å (a CAD part at 1 µm packed for that held 31 % of a real bilayer's lipids), 24 % at
// 10⁻³, and at a knot's 10⁻² rad/Å the packing never ends. Within limits of 1.12, 2.5·10⁻⁴ and 0.05
// the same part holds 62 % (72 % beside its proteins), the triangles beyond them checked copy by copy
// instead: 132 CPU s against 82, still under the red blood cell's surface of that area (185). The
// stretch allows the cube-sphere's 1.154 (make-mesh sphere, the virion's proxy): a large one stays
// packed whole. The bundled red blood cell (1.03, 1.1·10⁻⁴ rad/Å, a tilt of 0.007) is well within.
struct PackableDistortion {
  double stretch = 1.16;     // largest σ1 over the smallest σ2 of the triangles packed for
  double turn_rate = 2.5e-4; // rad per Å: a radius of curvature of 4,000 Å
  double tilt = 0.05;
  // No bound on the facets' sag: a neighbour's rise is the tilt times its distance (≤ 0.05 · 200 Å
  // for the widest pairs) whatever the sag, which only caps it (tiles::SurfaceDistortion::max_rise).
};
inline constexpr PackableDistortion kPackableDistortion{};

struct MeshSurfacePlan {
  std::vector<char> checked;  // per triangle: 1 when its copies are all checked on the surface
  double tile_scale = 0.0;    // Å of surface per UV unit of the tiles (the chart's mean when rigid)
  double checked_area = 0.0;  // Å² of the checked triangles
  double area = 0.0;          // Å²
};

struct MembraneSurfacePlan {
  tiles::SurfaceDistortion pack_for;  // zero: packed rigid
  bool whole_surface = true;          // every copy checked (tiles rigid)
  std::vector<MeshSurfacePlan> meshes;  // one per mesh given, in order
  double copies = 0.0;          // the copies the membrane puts on all its meshes (estimated)
  double checked_copies = 0.0;  // of those, on checked triangles (all of them when whole_surface)
};

// Plans one membrane over the meshes that wear it (charted: with UVs), putting `copies_per_a2` on
// them: rigid and checked everywhere when it puts at most `whole_surface_budget` copies or when
// more than half of them would stand on triangles beyond `limits`; otherwise packed for the
// largest distortion of the other triangles (the turn rate with 5 % for what corner normals miss).
// Deterministic; `threads` only spreads the measuring.
MembraneSurfacePlan plan_membrane_surface(std::span<const mesh::ProxyMesh* const> meshes, double copies_per_a2,
                                          double smooth, double whole_surface_budget, int threads,
                                          const PackableDistortion& limits = kPackableDistortion);

}  // namespace nano::scene_bake
