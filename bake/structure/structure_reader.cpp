#include "bake/structure/structure_reader.hpp"

#include <algorithm>
#include <cctype>
#include <map>

#include "bake/structure/element.hpp"
#include "bake/structure/mmcif_parser.hpp"
#include "bake/structure/pdb_parser.hpp"
#include "bake/structure/structure_text.hpp"
#include "common/error.hpp"

namespace nano::structure {
namespace {

std::string lowercase_extension(std::filesystem::path path) {
  auto lower = [](std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  std::string ext = lower(path.extension().string());
  if (ext == ".gz") ext = lower(path.stem().extension().string());
  return ext;
}

bool starts_like_mmcif(std::string_view text) {
  std::size_t pos = 0;
  while (pos < text.size()) {
    const char c = text[pos];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
      ++pos;
    } else if (c == '#') {
      const std::size_t newline = text.find('\n', pos);
      pos = newline == std::string_view::npos ? text.size() : newline + 1;
    } else {
      return text.size() - pos >= 5 && (text.substr(pos, 5) == "data_" || text.substr(pos, 5) == "DATA_");
    }
  }
  return false;
}

// Fills in radii; unknown elements get the fallback radius and one warning per element.
void assign_radii(Molecule& molecule) {
  std::map<std::string, std::size_t> unknown_counts;
  for (Atom& atom : molecule.atoms) {
    if (auto radius = van_der_waals_radius(atom.element)) {
      atom.radius = *radius;
    } else {
      atom.radius = kFallbackVdwRadius;
      ++unknown_counts[atom.element];
    }
  }
  for (const auto& [element, count] : unknown_counts)
    molecule.warnings.push_back("element '" + (element.empty() ? std::string("?") : element) +
                                "' has no van der Waals radius in the table: " + std::to_string(count) +
                                " atom(s) use the fallback 1.7 A");
}

}  // namespace

StructureFormat detect_structure_format(const std::filesystem::path& path, std::string_view text) {
  const std::string ext = lowercase_extension(path);
  if (ext == ".cif" || ext == ".mmcif") return StructureFormat::Mmcif;
  if (ext == ".pdb" || ext == ".ent") return StructureFormat::Pdb;
  return starts_like_mmcif(text) ? StructureFormat::Mmcif : StructureFormat::Pdb;
}

Molecule molecule_from_text(std::string_view text, StructureFormat format, const std::string& source,
                            const SelectionOptions& options) {
  ParsedStructure parsed = format == StructureFormat::Mmcif ? parse_mmcif(text, source) : parse_pdb(text, source);
  const std::size_t parsed_count = parsed.atoms.size();
  Molecule molecule;
  molecule.source = source;
  molecule.format = format;
  molecule.model_count = parsed.model_count;
  Selection selection = select_atoms(std::move(parsed.atoms), options);
  molecule.atoms = std::move(selection.atoms);
  if (molecule.atoms.empty())
    throw InputError(source, "whole file", "the selection (model, water, hydrogen policy) removed all " +
                                               std::to_string(parsed_count) + " atom records: nothing left");
  if (selection.duplicates_without_alt_loc > 0)
    molecule.warnings.push_back(std::to_string(selection.duplicates_without_alt_loc) +
                                " atom record(s) repeat the (chain, residue number, insertion code, atom name) of an "
                                "earlier atom without an alternate-location id and were dropped; residue numbers may "
                                "wrap or chains may be unnamed");
  assign_radii(molecule);
  return molecule;
}

Molecule read_molecule(const std::filesystem::path& path, const SelectionOptions& options) {
  const std::string text = read_structure_text(path);
  return molecule_from_text(text, detect_structure_format(path, text), path.string(), options);
}

}  // namespace nano::structure
