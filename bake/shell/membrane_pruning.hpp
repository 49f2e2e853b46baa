#pragma once
// The membrane on its real surface: which copies the triangles own that would clash once placed.
// A Wang set is collision-free in flat tile space; the chart then stretches and shears it, the
// normals turn and tilt, and across a UV seam two charts lay unrelated parts of the tiling side by
// side. Rather than pack every tile for the worst a mesh can do anywhere (which empties most of a
// lipid patch), the baker places the copies where they really go, finds the pairs of copies whose
// atoms come closer than the clash rule allows, and drops as few copies as it can: a greedy
// independent set that keeps proteins before lipids. The dropped copies are stored per triangle
// (package sections triangle_drops / dropped_copies) and skipped by the oracle and the shader.
// A Wang square may also carry alternates (tiles::Instance::alternate): another conformer at the
// place of a copy the surface may push into a clash, the same lipid a hair aside or turned, a lipid
// the tiles refused beside a protein. They are decided after every other copy, in a second round
// that places only those whose place no kept copy of their type holds: each is shown (listed with
// the drops) where it clashes with nothing shown, fewer clashes first.
#include <cstdint>
#include <optional>
#include <vector>

#include "bake/mesh/proxy_mesh.hpp"
#include "bake/shell/membrane_mapping.hpp"
#include "bake/tiles/molecule_type.hpp"

namespace nano::shell {

struct PruningSettings {
  // Atoms of two kept copies stay at least clearance · (r1 + r2) apart (the bake tests check 0.6;
  // the baker keeps a hair more so float rounding of the placement can never tip a pair over).
  float clearance = 0.6012f;
  // A membrane owning at most this many copies is checked everywhere; a larger one only within
  // reach of a UV seam, trusting its tile set to survive what its charts do elsewhere.
  std::uint64_t whole_surface_budget = 600000;
  // Set by a caller whose tiles were packed rigid (they survive nothing a chart does): check
  // everywhere whatever the count.
  bool whole_surface = false;
  // Per triangle (empty: none): every copy the triangle owns is checked, as are its neighbours'
  // within reach of it — the mesh distorts the tiles there beyond what the set was packed for, or a
  // copy stands there that the tiling does not vouch for (a per-compartment protein).
  std::vector<char> checked_triangles;
  // The copies the triangles own, when the caller has counted them already (the shell offsets
  // enumerate every one): spares a pass over 10^8 copies of a cell. Absent: counted here.
  std::optional<std::uint64_t> owned_copies;
  // Copies dropped before the pruning (per triangle, ascending keys: limit_copies): not placed, so
  // they take nothing from their neighbours; they are dropped in the result as well.
  std::vector<std::vector<std::uint32_t>> dropped_before;
};

struct PrunedMembrane {
  // Per triangle, ascending membrane_copy_key(slot, instance) of the copies it drops and of the
  // alternates it shows (gpu::membrane_copy_listed_shows): section dropped_copies.
  std::vector<std::vector<std::uint32_t>> dropped;
  std::vector<std::uint64_t> dropped_by_type;       // indexed like the mapping's molecule types; alternates not counted
  std::vector<std::uint64_t> alternates_by_type;    // alternates shown, indexed likewise
  std::uint64_t owned_copies = 0;                   // every copy the triangles own, dropped or not
  bool whole_surface = false;                       // all owned copies checked, not only near seams
  std::uint64_t checked_triangles = 0;              // triangles whose copies were all checked (whole_surface: all)
  std::uint64_t checked_copies = 0;                 // copies placed and tested against their neighbours
  std::uint64_t atom_pairs = 0;                     // pairs of atoms of two small copies whose distance was taken
  std::uint64_t copy_pairs_tested = 0;              // pairs of copies with a large one (a protein) tested whole
  std::uint64_t clashing_pairs = 0;                 // pairs of copies with atoms closer than the clearance

  std::uint64_t dropped_count() const;
};

// `mesh` is the mesh the mapping was built from (its UV islands tell which copies share one flat
// tiling); `types` the molecule types the set's instances index (their atoms decide clashes).
// Deterministic for the inputs, whatever `threads`.
PrunedMembrane prune_membrane(const MembraneMapping& mapping, const mesh::ProxyMesh& mesh,
                              const std::vector<tiles::MoleculeType>& types, const PruningSettings& settings,
                              int threads);

// Where an independent set (`kept`: no two copies that clash) keeps one copy whose place two dropped
// ones could take (each clashing with it alone among the kept, and not with each other; and no
// unswappable copy that it alone holds out), they take it, until no such copy remains. `conflicts` per copy, ascending, symmetric; only copies marked
// `swappable` change (the pruning's lipids: its proteins stay as decided). The set stays
// independent, every dropped copy still clashes with a kept one, and the kept count only grows.
void swap_one_for_two(const std::vector<std::vector<std::uint32_t>>& conflicts, const std::vector<char>& swappable,
                      std::vector<char>& kept);

// Keeps at most `count` of the copies of molecule type `type` that the triangles own and `pruned`
// keeps, spread over the surface (farthest-point sampling from the first in enumeration order: each
// next copy is the one farthest from those already kept), and adds the others to `pruned.dropped`.
// Returns how many it keeps. Run before prune_membrane (PruningSettings::dropped_before) on tiles
// whose lipids were laid through the type, so that a dropped copy leaves bilayer, not a hole.
// `kept_on`, when given, receives the triangles holding the kept copies.
std::uint64_t limit_copies(const MembraneMapping& mapping, PrunedMembrane& pruned, std::uint32_t type, std::uint64_t count,
                           std::vector<std::uint32_t>* kept_on = nullptr);

}  // namespace nano::shell
