#pragma once
// PDB (fixed-column) parser: ATOM/HETATM records of every model, tolerant of short lines where
// the format allows it (missing occupancy/element columns) and strict where it does not.
#include <string>
#include <string_view>

#include "bake/structure/parsed_structure.hpp"

namespace nano::structure {

// `file_name` only labels error messages. Throws InputError on a malformed ATOM/HETATM record
// (truncated before the coordinates, non-numeric number fields) or if there are no atom records.
ParsedStructure parse_pdb(std::string_view text, const std::string& file_name);

}  // namespace nano::structure
