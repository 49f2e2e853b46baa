#pragma once
// Whether what a scene asks for can physically fit, decided from numbers before any tile is
// packed: a membrane protein's density against its footprint in the leaflet, lipids against their
// own cross-section, a soluble's concentration against its volume (and all solubles together
// against the cube), per-compartment counts against the surface, molecules against their tile,
// meshes against the precision of the coordinates the runtime traces in; and nothing emptied or
// detached (#39): no amount that rounds to no copy (in a tile set or on one compartment), no depth
// that leaves a protein clear of its bilayer, no clearance that leaves a soluble no room. Each
// refusal is an InputError naming the scene file, the key path, the value and the largest (or
// smallest) value that can work. Pure arithmetic on the description and on measures the baker takes of the
// molecules and meshes, so the scene fuzzer exercises it without reading a file.
#include <cstddef>
#include <span>
#include <string>
#include <string_view>

#include "bake/scene/scene_description.hpp"

namespace nano::scene {

// One molecule of the scene as the tile packers will see it (Å, Å², Å³).
struct MoleculeMeasure {
  double bounding_radius = 0.0;  // about its centroid: the reach a soluble copy needs in its cube
  double lateral_radius = 0.0;   // about its up axis: the reach a membrane copy needs in its tile
  // Standing along +z at the given depth (the protein's), the area its atoms take of the outer
  // (0 < z < half_thickness) and inner leaflet, projected on the membrane plane.
  double outer_footprint = 0.0, inner_footprint = 0.0;
  double height = 0.0;  // extent along its up axis: copies side by side fill a slab this thick
  double volume = 0.0;  // union of its atoms' spheres
  // Along its up axis from its centre, how far its atoms reach below and above it (both >= 0, and
  // reach_below + reach_above = height): a copy standing at depth d spans [d - below, d + above].
  double reach_below = 0.0, reach_above = 0.0;
};

// A compartment's mesh after units, scale, "diameter" or "volume" (Å, Å², Å³).
struct CompartmentMeasure {
  double area = 0.0;
  double volume = 0.0;
  double extent = 0.0;  // largest distance of a vertex from the compartment's origin
  std::size_t triangles = 0;
  double bilayer_thickness = 0.0;  // of the membrane it wears (0: none)
  // No point inside the mesh lies farther than this from its surface (an upper bound; 0: not
  // measured): a soluble copy is kept only as far as its bounding radius plus its clearance.
  double deepest = 0.0;
};

// The largest concentration at which solubles still fit: volume fraction of their atoms.
inline constexpr double kMaxSolubleVolumeFraction = 0.74;  // close-packed spheres
// The largest share of a leaflet (or of a protein's own layer) membrane proteins may cover.
inline constexpr double kMaxLeafletCoverage = 1.0;
// Compartment coordinates are float32 on the GPU: beyond 2^20 Å their spacing exceeds 1/8 Å.
inline constexpr double kMaxCompartmentExtent = 1048576.0;
// Tiles and cubes: below an atom, nothing fits; above 10 µm, a single tile set is more copies
// than a machine holds.
inline constexpr double kMinTileSize = 10.0, kMaxTileSize = 100000.0;
// A lipid fill's two leaflets meet at the mid-surface: the tail ends of each leaflet stand at most
// this far from it (apart, the bilayer would be two sheets with vacuum between; overlapping, the
// tails of one leaflet would run through the other's).
inline constexpr double kLeafletMeetTolerance = 3.0;
// Proxy meshes are low-poly.
inline constexpr double kMaxMeshTriangles = 4e6;

// A membrane protein's amount as copies per Å² of membrane (per_um2 or per tile of the membrane's
// Wang squares), a soluble's as copies per Å³ (mM or per µm³).
double copies_per_a2(const MembraneDescription& membrane, const SurfaceAbundance& amount);
double copies_per_a3(const VolumeAbundance& amount);

// The key path of a membrane protein's amount, or of a soluble's, in the unit the scene wrote it
// in ("membranes.envelope.proteins[2].density_per_um2").
std::string amount_key(const MembraneDescription& membrane, std::size_t protein);
std::string amount_key(const SolubleDescription& soluble, std::size_t molecule);
// The key path of any field of a membrane's protein entry ("membranes.envelope.proteins[0].per_compartment").
std::string protein_key(const MembraneDescription& membrane, std::size_t protein, const std::string& field);

// Checks on the description alone: tile and cube sizes, mesh sizes, instance counts, random
// placements against their boxes. Run before any file is read.
void check_scene_amounts(const SceneDescription& scene);

// Checks that need the molecules (one measure per scene.molecules entry, in order): densities,
// concentrations, molecules against their tiles. A lipid patch is not checked here: it gives way
// to the proteins wherever they stand.
void check_molecule_amounts(const SceneDescription& scene, std::span<const MoleculeMeasure> molecules);

// Checks of one compartment's mesh: extent against float precision, per-compartment counts
// against its area, each membrane protein's depth (and a lipid fill's leaflet offset) against the
// bilayer it must reach.
void check_compartment_amounts(const SceneDescription& scene, std::size_t compartment, const CompartmentMeasure& mesh,
                               std::span<const MoleculeMeasure> molecules);

// Checks of one compartment's mesh as baked (after any remeshing), before the heavy stages: every
// molecule its membrane and soluble list with a non-zero amount can have a copy there. At least
// one copy expected on its surface (density x area) or inside it (concentration x volume), and,
// when mesh.deepest is measured, room for a soluble's copy: it is kept only where its bounding
// sphere stays the soluble's clearance away from the surface.
void check_compartment_room(const SceneDescription& scene, std::size_t compartment, const CompartmentMeasure& mesh,
                            std::span<const MoleculeMeasure> molecules);

// A membrane's lipid patch as its tiles lay it: at most this many places per tile in each leaflet
// (the patch's lipids of that leaflet times its repeats along each tile edge).
struct PatchPlaces {
  double outer = 0.0, inner = 0.0;
};

// Each lipid_mix species takes round(fraction x places) of each leaflet's places per tile: a
// non-zero fraction that rounds to none is refused with the least fraction that takes a place.
void check_lipid_mix_amounts(const SceneDescription& scene, std::size_t membrane, const PatchPlaces& places);

// Lipids of each kind in one leaflet (kind name -> count): a patch's own, or the copies a bake keeps.
using LeafletCounts = std::vector<std::pair<std::string, std::uint64_t>>;

// Against the membrane's `lipid_patch.leaflets` (a membrane without them passes): in each leaflet
// every kind's share within kLeafletShareTolerance mol % of the share asked, and a kind asked a
// non-zero share has at least one lipid there. `whose` says what the counts are ("the patch file
// holds", "the bake keeps"); the refusal names the leaflet, the kind, both shares and the counts.
void check_leaflet_shares(const SceneDescription& scene, std::size_t membrane, const LeafletCounts& outer,
                          const LeafletCounts& inner, std::string_view whose);

// Random placements against their boxes (one bounding radius per compartment, Å): run before
// expand_random_instances, whose work grows with the count.
void check_placement_amounts(const SceneDescription& scene, std::span<const double> bounding_radii);

}  // namespace nano::scene
