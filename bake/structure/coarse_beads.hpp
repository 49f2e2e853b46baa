#pragma once
// The level of detail's coarse model of a molecule: its atoms merged into beads, each a sphere that
// holds the spheres of its atoms, so a copy drawn as beads covers at least what its atoms cover.
// A bead is a residue when the residue fits in a sphere of kResidueBeadRadius; a larger residue
// (a lipid, a nucleotide, a big ligand) is cut into fragments: its atoms whose centres share a cell
// of kFragmentEdge Å. Computed by the baker, stored per molecule type (format sections beads and
// bead_ranges) and drawn by the renderer when an atom spans less than the --lod threshold.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "bake/structure/atom.hpp"

namespace nano::structure {

inline constexpr double kResidueBeadRadius = 6.0;  // Å: a whole amino-acid residue (Trp ≈ 5.5 Å)
inline constexpr double kFragmentEdge = 8.0;       // Å: cell edge cutting larger residues

struct CoarseBead {
  glm::dvec3 centre{0.0};           // centroid of the atom centres, molecule space
  double radius = 0.0;              // holds every atom sphere of the bead
  std::uint32_t representative = 0;  // index into the atoms: the one nearest the centre (a hit reports it)
  std::uint32_t atom_count = 0;
};

// Every atom in exactly one bead. Deterministic: depends only
// on the atoms and their order (residues by first atom, a residue's fragments likewise).
// Throws std::invalid_argument for a non-finite position or radius: a caller's bug, not bad input
// (the structure readers refuse non-finite coordinates and give every atom a radius; a scene's
// stand-in spheres are refused unless their radius lies in (0, 1000] Å).
std::vector<CoarseBead> coarse_beads(const std::vector<Atom>& atoms);

}  // namespace nano::structure
