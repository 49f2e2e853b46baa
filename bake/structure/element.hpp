#pragma once
// Chemical elements: normalising symbols, guessing them from PDB atom names, and their radii.
#include <optional>
#include <string>
#include <string_view>

namespace nano::structure {

// Radius used for an element missing from the table (Mol*'s DefaultVdwRadius, BIOLOGY.md §3).
inline constexpr double kFallbackVdwRadius = 1.7;

// "FE", " fe", "Fe" -> "Fe"; deuterium "D" -> "H" (same radius, same chemistry for rendering).
// Returns "" when the text holds no letters.
std::string normalize_element_symbol(std::string_view text);

// True for the 118 element symbols (case-insensitive).
bool is_element_symbol(std::string_view symbol);

// Infers the element from the 4-character PDB atom-name field (columns 13-16) following the
// PDB convention: one-letter elements are right-justified in columns 13-14 (" CA " is a carbon
// alpha, "CA  " calcium); a digit in column 13 marks old-style hydrogen names ("1HB ");
// a 4-character name starting with H ("HG21") is a hydrogen, not mercury.
// Returns "" when nothing sensible can be inferred.
std::string infer_element_from_pdb_atom_name(std::string_view name_field);

// Infers the element from a bare atom name as mmCIF writes it ("CA", "FE", "HG21"), given the
// residue name: an atom named like its residue ("FE" in "FE", "CA" in "CA") is that ion.
std::string infer_element_from_atom_name(std::string_view atom_name, std::string_view residue_name);

// Mantina et al. 2009 van der Waals radius in Å (the Mol*/NGL table), or nullopt if unknown.
std::optional<double> van_der_waals_radius(std::string_view normalized_symbol);

}  // namespace nano::structure
