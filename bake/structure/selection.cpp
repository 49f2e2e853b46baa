#include "bake/structure/selection.hpp"

#include <unordered_map>

namespace nano::structure {
namespace {

std::string identity_key(const Atom& atom) {
  std::string key;
  key.reserve(32);
  key += std::to_string(atom.model_index);
  key += '\x1f';
  key += atom.chain;
  key += '\x1f';
  key += std::to_string(atom.residue_number);
  key += '\x1f';
  key += atom.insertion_code;
  key += '\x1f';
  key += atom.atom_name;
  return key;
}

}  // namespace

bool is_water_residue(const std::string& name) {
  return name == "HOH" || name == "WAT" || name == "DOD" || name == "H2O";
}

Selection select_atoms(std::vector<Atom> atoms, const SelectionOptions& options) {
  Selection selection;
  selection.atoms.reserve(atoms.size());
  std::unordered_map<std::string, std::size_t> slot_of_key;
  slot_of_key.reserve(atoms.size());
  for (Atom& atom : atoms) {
    if (!options.all_models && atom.model_index != 0) continue;
    if (!options.keep_water && is_water_residue(atom.residue_name)) continue;
    if (!options.keep_hydrogens && atom.element == "H") continue;
    const auto [it, inserted] = slot_of_key.try_emplace(identity_key(atom), selection.atoms.size());
    if (inserted) {
      selection.atoms.push_back(std::move(atom));
      continue;
    }
    Atom& kept = selection.atoms[it->second];
    if (atom.alt_loc == ' ' && kept.alt_loc == ' ') ++selection.duplicates_without_alt_loc;
    if (atom.occupancy > kept.occupancy) kept = std::move(atom);
  }
  return selection;
}

}  // namespace nano::structure
