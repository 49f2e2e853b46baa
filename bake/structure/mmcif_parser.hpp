#pragma once
// mmCIF parser: reads the _atom_site category of the first data block, in any column order,
// preferring the author (auth_*) identifiers that PDB-format files also use.
#include <string>
#include <string_view>

#include "bake/structure/parsed_structure.hpp"

namespace nano::structure {

// `file_name` only labels error messages. Throws InputError on tokenizer errors, a loop whose
// value count is not a multiple of its column count, missing coordinate or atom-name columns,
// non-numeric numbers, or when the first data block has no atoms.
ParsedStructure parse_mmcif(std::string_view text, const std::string& file_name);

}  // namespace nano::structure
