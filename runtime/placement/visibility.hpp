#pragma once
// What a picture leaves out, by name: whole compartments (every instance of a red cell, its
// membrane and its interior) and molecule types (wherever they stand: membranes, cores, the
// medium). The renderer and the CPU oracle apply the same Visibility, so `verify --hide` compares
// like with like. The medium as a whole is its own switch (RenderSettings::show_medium,
// CopyOptions::medium): hiding a cell keeps the plasma out of the cell's place, as in the scene.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "format/package.hpp"

namespace nano::placement {

struct Visibility {
  std::vector<std::uint8_t> hidden_compartments;    // empty, or one per compartment: 1 = hidden
  std::vector<std::uint8_t> hidden_molecule_types;  // empty, or one per molecule type: 1 = hidden

  bool compartment_hidden(std::uint32_t compartment) const {
    return compartment < hidden_compartments.size() && hidden_compartments[compartment] != 0;
  }
  bool molecule_type_hidden(std::uint32_t type) const {
    return type < hidden_molecule_types.size() && hidden_molecule_types[type] != 0;
  }
  bool hides_compartments() const;
  bool hides_molecule_types() const;
  bool hides_anything() const { return hides_compartments() || hides_molecule_types(); }
  bool operator==(const Visibility&) const = default;
};

// A name a user may hide: "medium", a compartment's or a molecule type's name from the package.
struct HideableName {
  enum class Kind : std::uint8_t { medium, compartment, molecule_type };
  Kind kind;
  std::string name;
  std::vector<std::uint32_t> indices;  // the compartments or molecule types of that name (none for medium)
};

// Every name `--hide` accepts for `package`, in package order (medium first when the package has
// one; a name shared by several molecule types is listed once, naming them all).
std::vector<HideableName> hideable_names(const format::Package& package);

// How many of `names` `text` names (bare, or qualified compartment:NAME / molecule:NAME): 1 is a
// valid --hide name, 0 unknown, 2 ambiguous.
std::size_t hideable_matches(std::span<const HideableName> names, const std::string& text);
// "medium, compartment:red_cell, molecule:POPC, ..." for messages.
std::string hideable_listing(std::span<const HideableName> names);

// The compartments and molecule types `names` hide (names as hideable_names lists them, or
// qualified "compartment:NAME" / "molecule:NAME" where a compartment and a molecule type share a
// name; "medium" is skipped: the caller's switch). Throws nano::InputError for `option` naming the
// package and listing the names it has, for an unknown or ambiguous name.
Visibility resolve_hidden(const format::Package& package, std::span<const std::string> names, const std::string& option = "--hide");

}  // namespace nano::placement
