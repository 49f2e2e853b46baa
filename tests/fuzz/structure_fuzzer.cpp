// libFuzzer target: arbitrary bytes through one structure reader. fuzz_structure is nano_fuzzer's
// reader for all three entries, NANO_FUZZ_READER picking one per process (fuzz_main.cpp); the
// entry is the format the bytes are taken to be, or none:
//   pdb    parse_pdb, then molecule_from_text (selection, radii) as PDB
//   mmcif  parse_mmcif, then molecule_from_text as mmCIF
//   gzip   no format: the bytes go the way of a file whose name names none (model.gz):
//          structure_text_from_bytes (gzip inflation, binary rejection), then, when that gives a
//          text, the format read_molecule would detect and molecule_from_text
// Rejection as an InputError is the expected outcome; anything else (another exception, a crash, a
// sanitizer report, a leak, an allocation over -rss_limit_mb, a hang) is a finding, and so is an
// accepted structure that breaks what the readers promise: atoms, finite coordinates and
// occupancies, model indices below the model count, lines within the text, and after the selection
// at least one atom, each with a positive finite radius.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "bake/structure/mmcif_parser.hpp"
#include "bake/structure/pdb_parser.hpp"
#include "bake/structure/structure_reader.hpp"
#include "bake/structure/structure_text.hpp"
#include "common/error.hpp"

namespace {

using namespace nano::structure;

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "structure fuzzer: %s\n", what.c_str());
  std::abort();
}

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::size_t line_count(std::string_view text) { return std::size_t(std::count(text.begin(), text.end(), '\n')) + 1; }

void check_atoms(const std::vector<Atom>& atoms, int model_count, std::string_view text, const char* stage) {
  const std::size_t lines = line_count(text);
  for (const Atom& atom : atoms) {
    if (!finite(atom.position)) finding(std::string(stage) + ": accepted atom has a non-finite coordinate");
    if (!std::isfinite(atom.occupancy)) finding(std::string(stage) + ": accepted atom has a non-finite occupancy");
    if (atom.model_index < 0 || atom.model_index >= model_count)
      finding(std::string(stage) + ": accepted atom's model index is not below the model count");
    if (atom.line < 1 || atom.line > lines) finding(std::string(stage) + ": accepted atom's line is not in the text");
  }
}

void check_parsed(const ParsedStructure& parsed, std::string_view text) {
  if (parsed.atoms.empty()) finding("parser accepted a structure without atoms");
  check_atoms(parsed.atoms, parsed.model_count, text, "parser");
}

// The molecule the baker would get, under the default selection and under the one that keeps most.
void check_molecules(std::string_view text, StructureFormat format, const std::string& name) {
  for (const SelectionOptions& options : {SelectionOptions{}, SelectionOptions{.all_models = true, .keep_water = true}}) {
    const Molecule molecule = molecule_from_text(text, format, name, options);
    if (molecule.atoms.empty()) finding("molecule_from_text accepted a molecule without atoms");
    check_atoms(molecule.atoms, molecule.model_count, text, "molecule_from_text");
    for (const Atom& atom : molecule.atoms)
      if (!(atom.radius > 0.0) || !std::isfinite(atom.radius)) finding("molecule_from_text: an atom has no radius");
  }
}

void run(std::optional<StructureFormat> format, std::string_view bytes) {
  if (format == StructureFormat::Pdb) {
    check_parsed(parse_pdb(bytes, "fuzz.pdb"), bytes);
    check_molecules(bytes, StructureFormat::Pdb, "fuzz.pdb");
  } else if (format == StructureFormat::Mmcif) {
    check_parsed(parse_mmcif(bytes, "fuzz.cif"), bytes);
    check_molecules(bytes, StructureFormat::Mmcif, "fuzz.cif");
  } else {
    // A name without a format of its own, so the content decides, as for "model.gz".
    const std::string name = "fuzz.gz";
    const std::string text = structure_text_from_bytes(std::string(bytes), name);
    check_molecules(text, detect_structure_format(name, text), name);
  }
}

}  // namespace

namespace nano::fuzz {

void fuzz_structure(std::optional<structure::StructureFormat> format, std::span<const std::byte> bytes) {
  try {
    run(format, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  } catch (const InputError&) {
  }
}

}  // namespace nano::fuzz
