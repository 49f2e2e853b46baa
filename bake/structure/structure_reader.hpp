#pragma once
// Reads a PDB or mmCIF file (optionally gzipped) into one molecule: parse, select, assign radii.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "bake/structure/atom.hpp"
#include "bake/structure/selection.hpp"

namespace nano::structure {

enum class StructureFormat { Pdb, Mmcif };

struct Molecule {
  std::string source;           // the path as given
  StructureFormat format = StructureFormat::Pdb;
  int model_count = 0;          // models in the file, whatever the selection
  std::vector<Atom> atoms;      // selected atoms, radius filled in
  std::vector<std::string> warnings;
};

// Decides the format from the name (.cif/.mmcif vs .pdb/.ent, ignoring a trailing .gz) and,
// for any other name, from the content (an mmCIF file starts with a data_ header).
StructureFormat detect_structure_format(const std::filesystem::path& path, std::string_view text);

// Parses `text` as `format` and applies the selection policy. Throws InputError on bad input,
// including when the selection leaves no atom.
Molecule molecule_from_text(std::string_view text, StructureFormat format, const std::string& source,
                            const SelectionOptions& options);

// read_structure_text + detect_structure_format + molecule_from_text.
Molecule read_molecule(const std::filesystem::path& path, const SelectionOptions& options);

}  // namespace nano::structure
