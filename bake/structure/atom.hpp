#pragma once
// One atom as read from a PDB or mmCIF file, with the metadata later stages need for picking.
#include <climits>
#include <cstddef>
#include <string>

#include <glm/vec3.hpp>

namespace nano::structure {

// mmCIF may leave a residue number unknown ('.' or '?'); this value stands for "none" so that
// such atoms still dedupe among themselves instead of colliding with a real residue 0.
inline constexpr int kNoResidueNumber = INT_MIN;

// No structure reaches this far from its own origin (a PDB coordinate field holds at most 9999.999;
// the largest assemblies in the PDB span a few thousand Å): a coordinate beyond it is a broken file,
// and further on it would overflow the bake's float and integer grids.
inline constexpr double kMaxCoordinate = 1e6;

struct Atom {
  glm::dvec3 position{0.0};
  double occupancy = 1.0;
  double radius = 0.0;           // van der Waals radius, filled in once the element is final
  std::string chain;             // PDB column 22 / auth_asym_id; may be empty
  std::string residue_name;
  int residue_number = kNoResidueNumber;
  std::string insertion_code;    // empty when none
  std::string atom_name;
  std::string element;           // normalised symbol: "C", "Fe"; empty when it cannot be known
  char alt_loc = ' ';            // ' ' when none; kept to tell alternate locations from clashes
  bool hetatm = false;
  int model_index = 0;           // 0-based, in order of appearance in the file
  std::size_t line = 0;          // 1-based line of the record, for messages
};

}  // namespace nano::structure
