#pragma once
// Number parsing shared by the PDB and mmCIF parsers: locale-free, allocation-free, and strict
// (the whole field must be the number, apart from surrounding blanks).
#include <optional>
#include <string_view>

namespace nano::structure {

std::string_view trim_blanks(std::string_view text);

// Parses a decimal such as "  -12.345", "1e3" or "+4". nullopt if the field is not exactly one number.
std::optional<double> parse_real(std::string_view field);

// Parses a decimal integer such as " 42" or "-7". nullopt otherwise.
std::optional<int> parse_integer(std::string_view field);

// Decodes a PDB residue number of `width` columns: decimal, or hybrid-36 (A000..ZZZZ then
// a000..zzzz for width 4) as written for more than 9999 residues. nullopt if neither.
std::optional<int> parse_hybrid36(std::string_view field, int width);

}  // namespace nano::structure
