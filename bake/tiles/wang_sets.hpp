#pragma once
// The two sets the scene baker asks for: Wang squares for a membrane and Wang cubes for solubles.
// Both are collision-free at atom level (clearance x sum of radii) in EVERY valid tiling (two
// lipids of a LipidPatch: the patch's own clearance).
#include "bake/tiles/collision_shape.hpp"
#include "bake/tiles/wang_set.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace nano::tiles {

// Copies per Å³ of a concentration: mM * 1e-3 mol/L * N_A / (1e27 Å³/L); returned per µm³ (1e12 Å³).
double copies_per_um3_from_millimolar(double millimolar);

struct GenerationBudget {
  float clearance = 1.0f;               // atoms of different copies stay >= clearance * (r1 + r2) apart
  int attempts_per_copy = 200;          // dart-throwing candidates per wanted copy and unit
  int max_consecutive_failures = 1500;  // give up on a unit after this many misses in a row
  // When random sequential addition ends short of a required molecule's density: at most this many
  // rounds of shaking every copy of the required molecules (small clash-free moves inside their
  // zones) and inserting more into the largest gaps, stopping once the density is met; 0 = plain
  // random sequential addition. Haemoglobin at 5 mM in 250 Å cubes needs ~100-200 rounds (~3 s).
  int relaxation_rounds = 300;
  int threads = 1;  // worker threads (unit_packer.hpp: PackerSettings::threads); the set does not depend on them
};

struct MembraneMolecule {
  uint32_t type = 0;           // index into the request's types
  double copies_per_um2 = 0.0;
  float depth = 0.f;           // tile-space z of the centre (Å along the membrane normal)
  // Copies the baker may drop on the surface (a per-compartment count): the lipid patch is laid as
  // if they were absent, so a dropped copy leaves bilayer, not a hole; where a copy is kept, the
  // baker's pruning on the real surface removes the lipids it displaces (proteins first).
  bool lipids_displaced_on_surface = false;
};

// Two leaflets at z = ±leaflet_offset; upper copies stand along +z, lower ones are flipped.
struct LipidFill {
  uint32_t type = 0;
  float area_per_lipid = 65.f;  // Å² per lipid per leaflet (the target; reached as far as space allows)
  float leaflet_offset = 20.f;  // Å
};

// A bilayer cut from an equilibrated periodic patch (e.g. popc.pdb): each patch lipid is a copy
// of one of the request's types (typically one type per patch lipid: its own conformer; ~50 heavy
// atoms each, so even hundreds of types cost little). The patch is repeated n = round(edge /
// period) times per axis with lipid CENTRES rescaled by edge / (n period), making the layer one
// pattern periodic with the tile edge, identical across every tile edge. Lipids that then clash
// with each other (a compressed patch) are dropped once for the whole pattern; lipids touching a
// membrane molecule are dropped by the unit holding them, so neighbouring tiles agree. Each type's
// achieved density is in `densities` (requested = its density in the patch); never throws for
// density.
// Another lipid species laid in a patch's places: a fraction of each leaflet's places (outer: z > 0)
// takes one of its conformers (centroid at the place's x, y, its own height from its own patch's
// mid-plane, turned about the normal), chosen so that it fits among the lipids laid before it; a
// place where none fits keeps the base patch's lipid.
struct LipidSpecies {
  std::vector<Instance> conformers;  // x, y ignored; z from the species' own mid-plane (Å)
  float outer = 0.f, inner = 0.f;    // mole fractions of the leaflets' places
};

struct LipidPatch {
  std::vector<Instance> lipids;  // x, y anywhere (taken modulo the period); z from the mid-plane (Å)
  float period_x = 0.f, period_y = 0.f;  // Å, the patch's periodic box (CRYST1 a, b)
  // Between two patch lipids and between a patch lipid and a protein (proteins among themselves
  // keep the budget's clearance): an equilibrated
  // patch has heavy-atom contacts closer than 1.0 x (1.7 + 1.7) Å, so at 1.0 most of popc.pdb is
  // dropped as clashing (40% of its density kept around a spike per two 200 Å tiles, 85% at 0.8).
  float clearance = 0.8f;
  std::vector<LipidSpecies> mix;  // per leaflet, fractions add up to at most 1
};

struct MembraneTileRequest {
  std::vector<MoleculeType> types;
  float edge = 200.f;  // Å
  int colours = 2;     // per edge: a complete set of colours^4 squares
  std::vector<MembraneMolecule> molecules;
  std::optional<LipidFill> lipids;
  std::optional<LipidPatch> lipid_patch;  // instead of `lipids`, not together with it
  // Every pair of copies stays clash-free under whatever the meshes wearing the membrane can do
  // to tile space (ClashRule): chart stretch up to 1 + e (mesh::chart_anisotropy − 1, the charts
  // being scaled by their smallest stretch), normals turning κ rad/Å (mesh::normal_turn_rate) and
  // tilting from their faces (mesh::largest_normal_tilt). Zero: rigid tile space only.
  SurfaceDistortion surface;
  uint64_t seed = 1;
  GenerationBudget budget;
};

struct SolubleMolecule {
  uint32_t type = 0;
  double copies_per_um3 = 0.0;  // see copies_per_um3_from_millimolar
};

struct SolubleCubeRequest {
  std::vector<MoleculeType> types;
  float edge = 250.f;  // Å
  int colours = 2;     // per face direction
  int variants = 2;    // K tiles per incoming colour triple (K*C^3 cubes); 0 = complete set (C^6)
  std::vector<SolubleMolecule> molecules;
  uint64_t seed = 1;
  GenerationBudget budget;
};

// Throw InputError for a bad request (unknown type, negative density, a molecule wider than the
// tile edge, ...) and when a requested molecule ends more than 10% below its density
// (the message names it and the best density reached). The lipid fill never throws for density:
// its achieved value is in `densities` (both leaflets together).
WangSet make_membrane_tiles(const MembraneTileRequest& request);

// Alternates a membrane packed rigid (SurfaceDistortion::rigid) keeps per lipid of its patch: the
// lipid 1 Å aside four ways and turned half about the normal, shown where the lipid itself clashes.
inline constexpr int kAlternatesPerLaidLipid = 5;
WangSet make_soluble_cubes(const SolubleCubeRequest& request);

}  // namespace nano::tiles
