#pragma once
// Fills the units of a geometric Wang set (ALGORITHMS.md §2), generic over the lattice dimension D.
//
// A unit is anchored at a lattice point; its "mask" lists the lattice axes whose planes through the
// anchor its copies may cross:
//   mask with >= 2 axes: shared units (D = 2: the vertex unit; D = 3: the vertex unit and one edge
//                        unit per axis), identical at every anchor: they fill the corners;
//   mask of one axis a : one unit per (a, colour) — the copies straddling a face of that colour;
//   empty mask         : the interior unit of one tile.
// Per type, a copy's centre lies within `band` (its extent radius along lattice axes, at most
// edge/2) of the anchor along the mask axes and at least `band` inside the tile along the others, so
// its atoms stay in the tiles around the anchor (the unit's "support") and the zones of all units
// partition space. Units are filled in order shared -> faces -> interiors by random sequential
// addition, each candidate checked at atom level against every earlier unit (and itself) placed at
// every lattice offset where the two can meet in SOME valid tiling with overlapping supports:
// faces of the same axis at the same place must share the colour, an interior meets only its own
// faces, interiors never meet. Hence every valid tiling is collision-free.
// Counts: a unit's target is density x zone volume; the shortfall of each unit (rounding, or
// space) is carried to the next units in copies per tile, weighted by how often a unit occurs per
// tile (shared 1, face 1/C, interior 1/tiles), so the set's mean density meets the request.
#include "bake/tiles/collision_shape.hpp"
#include "bake/tiles/wang_set.hpp"

#include <glm/gtc/quaternion.hpp>

#include <string>
#include <vector>

namespace nano::tiles {

struct PlacementSpec {
  uint32_t type = 0;
  double copies_per_volume = 0.0;  // per Å^D of lattice measure (Å² for squares, Å³ for cubes)
  float band = 0.f;                // extent radius of any copy along the lattice axes (Å)
  bool uniform_rotation = false;   // cubes: uniform on SO(3); squares: spin about z after `base`
  glm::quat base{1.f, 0.f, 0.f, 0.f};
  float z = 0.f;                   // D = 2: tile-space z of the centre (membrane depth)
  bool densify = true;             // shaken and topped up by the densification pass (if enabled)
};

struct PackerSettings {
  float edge = 0.f;
  float clearance = 1.f;  // atoms of different copies stay >= clearance * (sum of radii) apart
  SurfaceDistortion surface;  // D = 2: what copies must survive on the meshes (ClashRule)
  uint64_t seed = 1;
  int attempts_per_copy = 200;          // candidate budget per targeted copy in a unit
  int max_consecutive_failures = 1500;  // a unit gives up on a type after this many misses in a row
  // Densification after the sequential fill while a `densify` spec is short of its density: up to
  // this many rounds of one shaking sweep over all copies of such specs followed by
  // relaxation_darts x (number of units) insertion attempts per short spec. 0 = off.
  int relaxation_rounds = 0;
  float relaxation_step = 0.25f;  // largest move per sweep, in bands (and twice that in radians)
  float relaxation_darts = 4.f;
  // Worker threads for what does not depend on order (the tiles' interiors, which never meet; the
  // layer's decisions; its refills, tried side by side and kept in order). The set is the same
  // whatever their number.
  int threads = 1;
};

// A layer laid over every tile after the specs are packed (a lipid bilayer cut from a periodic
// patch): tile-space copies forming one pattern periodic with the tile edge and clash-free with
// itself and its images one edge away. Each copy joins the unit whose zone (with `band`) holds its
// centre, and each instance of that unit keeps it unless it touches a packed copy the unit can meet
// in some tiling: one decision per unit instance, so neighbouring tiles always agree.
// Where a packed copy refuses a layer copy, up to refill_attempts other layer copies of the same
// side of z = 0 (the same leaflet) and the same kind, turned about z and moved up to 8 Å away from the refusing copy
// (and 3 Å across), are tried in its place.
struct FixedLayer {
  // x, y (and z for cubes) in [0, edge). Alternates (Instance::alternate) are kept where the packed
  // copies leave them room, but never refilled, counted in the density or checked against the layer.
  std::vector<Instance> copies;
  float band = 0.f;              // extent radius of any copy along the lattice axes, <= edge / 2
  // Atoms of a layer copy and of a packed copy stay >= clearance · (r1 + r2) apart (0: the
  // packer's clearance). A lipid packs closer against a protein than two proteins against each other.
  float clearance = 0.f;
  // 1024: the virion's M rims take 20 % of the refused lipids back (256: 14 %; 4096: 26 % at 6× the
  // time), which adds 1.1 % of a real bilayer's lipids.
  int refill_attempts = 1024;
  // Kind of each molecule type (the conformers of one lipid share it): a hole is refilled with a
  // conformer of its own kind, so that the composition asked is the one kept (drawn from the whole
  // leaflet, the sterol that fits where a four-tailed lipid does not took 11 % of a leaflet asked for
  // 4.5 % beside the virion's M dimers). Empty: any conformer of the leaflet.
  std::vector<uint32_t> kind_of_type;
  // Packed types the layer is laid through (neither refuses a layer copy nor is refilled around):
  // their clashes with the layer are settled later, on the real surface.
  std::vector<uint32_t> laid_through;
  // A membrane pruned on its whole surface: each layer copy a packed copy refuses stays as an
  // alternate, so that where the pruning drops that protein (a clash across a seam, no prism) its
  // place is not a hole down to the lumen but the lipids it displaced, wherever they fit.
  bool refused_stay_as_alternates = false;
};

struct PackedUnits {
  std::vector<WangTile> tiles;
  std::vector<double> achieved_per_volume;  // per spec, same unit as copies_per_volume
  std::vector<double> layer_per_volume;     // per molecule type: kept layer copies (empty without a layer)
};

// Specs are filled in the given order (put large molecules first). The caller has checked
// 0 < band <= edge / 2 for every spec and the layer, and lateral_stretch >= 0.
ClashRule clash_rule(const PackerSettings& settings, int dims);

PackedUnits pack_wang_units(const std::vector<CollisionShape>& shapes, const std::vector<PlacementSpec>& specs,
                            const WangColouring& colouring, const PackerSettings& settings,
                            const FixedLayer& layer = {});

// Tile-space box of all atoms of the instances (empty tile: a zero box at the origin).
void compute_atom_bounds(WangTile& tile, const std::vector<CollisionShape>& shapes);

}  // namespace nano::tiles
