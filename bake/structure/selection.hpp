#pragma once
// The default atom-selection policy of nanobake and its switches.
#include <string>
#include <vector>

#include "bake/structure/atom.hpp"

namespace nano::structure {

struct SelectionOptions {
  bool all_models = false;      // default: the first model only
  bool keep_water = false;      // default: HOH/WAT/DOD/H2O residues removed
  bool keep_hydrogens = true;   // H and D atoms kept when the file has them
};

struct Selection {
  std::vector<Atom> atoms;
  std::size_t duplicates_without_alt_loc = 0;  // dropped duplicates that were not alternate locations
};

bool is_water_residue(const std::string& residue_name);

// Applies, in order: model choice, water and hydrogen removal, then ONE ATOM PER (model, chain,
// residue number, insertion code, atom name): the highest occupancy wins, ties go to the atom
// earlier in the file. This resolves alternate locations, split residues included. The winner
// takes the place of the first atom with its key, so the output keeps file order.
Selection select_atoms(std::vector<Atom> atoms, const SelectionOptions& options);

}  // namespace nano::structure
