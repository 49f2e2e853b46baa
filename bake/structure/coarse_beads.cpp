#include "bake/structure/coarse_beads.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

#include <glm/geometric.hpp>

namespace nano::structure {
namespace {

using glm::dvec3;

// The atoms of one residue: chain, number, insertion code and name (mmCIF may leave the number
// unknown, so the name keeps two unnumbered residues apart).
using ResidueKey = std::tuple<std::string, int, std::string, std::string>;

CoarseBead bead_of(const std::vector<Atom>& atoms, const std::vector<std::uint32_t>& members) {
  CoarseBead bead;
  for (std::uint32_t a : members) bead.centre += atoms[a].position;
  bead.centre /= double(members.size());
  double nearest = INFINITY;
  for (std::uint32_t a : members) {
    const double from = glm::length(atoms[a].position - bead.centre);
    bead.radius = std::max(bead.radius, from + atoms[a].radius);
    if (from < nearest) nearest = from, bead.representative = a;
  }
  bead.atom_count = std::uint32_t(members.size());
  return bead;
}

}  // namespace

std::vector<CoarseBead> coarse_beads(const std::vector<Atom>& atoms) {
  for (std::size_t a = 0; a < atoms.size(); ++a) {
    const Atom& atom = atoms[a];
    if (!std::isfinite(atom.position.x) || !std::isfinite(atom.position.y) || !std::isfinite(atom.position.z) ||
        !(atom.radius > 0 && std::isfinite(atom.radius)))
      throw std::invalid_argument("atom " + std::to_string(a) + " has a non-finite position or no radius");
  }
  // Residues in order of their first atom.
  std::map<ResidueKey, std::size_t> residue_index;
  std::vector<std::vector<std::uint32_t>> residues;
  for (std::uint32_t a = 0; a < atoms.size(); ++a) {
    const Atom& atom = atoms[a];
    const auto [it, added] = residue_index.try_emplace(
        ResidueKey{atom.chain, atom.residue_number, atom.insertion_code, atom.residue_name}, residues.size());
    if (added) residues.emplace_back();
    residues[it->second].push_back(a);
  }
  std::vector<CoarseBead> beads;
  for (const std::vector<std::uint32_t>& residue : residues) {
    const CoarseBead whole = bead_of(atoms, residue);
    if (whole.radius <= kResidueBeadRadius) {
      beads.push_back(whole);
      continue;
    }
    // Fragments, in order of their first atom so the result does not depend on cell numbering.
    std::map<std::tuple<long, long, long>, std::size_t> cell_index;
    std::vector<std::vector<std::uint32_t>> fragments;
    for (std::uint32_t a : residue) {
      const dvec3 c = glm::floor(atoms[a].position / kFragmentEdge);
      const auto [it, added] = cell_index.try_emplace({long(c.x), long(c.y), long(c.z)}, fragments.size());
      if (added) fragments.emplace_back();
      fragments[it->second].push_back(a);
    }
    for (const std::vector<std::uint32_t>& fragment : fragments) beads.push_back(bead_of(atoms, fragment));
  }
  return beads;
}

}  // namespace nano::structure
