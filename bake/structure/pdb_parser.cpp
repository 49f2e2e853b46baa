#include "bake/structure/pdb_parser.hpp"

#include <cmath>
#include <cstring>

#include "bake/structure/element.hpp"
#include "bake/structure/field_parsing.hpp"
#include "common/error.hpp"

namespace nano::structure {
namespace {

// Columns are 1-based and inclusive as in the PDB specification; a field cut short by the end
// of the line yields what is there.
std::string_view columns(std::string_view line, std::size_t first, std::size_t last) {
  if (line.size() < first) return {};
  return line.substr(first - 1, std::min(last, line.size()) - (first - 1));
}

bool starts_with_record(std::string_view line, std::string_view record) {
  if (line.substr(0, record.size()) != record) return false;
  // "END" must not match "ENDMDL": the rest of the 6-column record name has to be blank.
  for (std::size_t i = record.size(); i < 6 && i < line.size(); ++i)
    if (line[i] != ' ') return false;
  return true;
}

class PdbParser {
public:
  PdbParser(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  ParsedStructure run() {
    std::size_t pos = 0, line_number = 0;
    while (pos < text_.size()) {
      const char* start = text_.data() + pos;
      const void* newline = std::memchr(start, '\n', text_.size() - pos);
      const std::size_t length = newline ? static_cast<const char*>(newline) - start : text_.size() - pos;
      std::string_view line(start, length);
      pos += length + 1;
      ++line_number;
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      if (line.size() < 3) continue;
      if (starts_with_record(line, "ATOM") || starts_with_record(line, "HETATM")) {
        atom_record(line, line_number);
      } else if (starts_with_record(line, "MODEL")) {
        if (atoms_in_model_) new_model_pending_ = true;  // MODEL without a preceding ENDMDL
      } else if (starts_with_record(line, "ENDMDL")) {
        if (atoms_in_model_) new_model_pending_ = true;
      } else if (starts_with_record(line, "END")) {
        break;
      }
    }
    if (result_.atoms.empty()) throw InputError(file_, "whole file", "no ATOM or HETATM records found: not a PDB structure");
    result_.model_count = model_index_ + 1;
    return std::move(result_);
  }

private:
  [[noreturn]] void fail(std::size_t line_number, const std::string& rule) const {
    throw InputError(file_, "line " + std::to_string(line_number), rule);
  }

  double coordinate(std::string_view line, std::size_t first, const char* axis, std::size_t line_number) const {
    const std::string_view field = columns(line, first, first + 7);
    const auto value = parse_real(field);
    if (value && std::isfinite(*value) && std::abs(*value) <= kMaxCoordinate) return *value;
    fail(line_number, std::string(record_name(line)) + " record has a " +
                          (!value ? "non-numeric " : std::isfinite(*value) ? "far-off (beyond ±1e6 Å) " : "non-finite ") + axis +
                          " coordinate '" + std::string(trim_blanks(field)) + "' (columns " + std::to_string(first) +
                          "-" + std::to_string(first + 7) + ")");
  }

  static std::string_view record_name(std::string_view line) { return line[0] == 'A' ? "ATOM" : "HETATM"; }

  void atom_record(std::string_view line, std::size_t line_number) {
    if (line.size() < 54)
      fail(line_number, std::string(record_name(line)) + " record is truncated: it has " + std::to_string(line.size()) +
                            " columns but the coordinates need columns 31-54");
    if (new_model_pending_) {
      ++model_index_;
      new_model_pending_ = false;
      atoms_in_model_ = false;
    }
    Atom atom;
    atom.hetatm = line[0] == 'H';
    atom.line = line_number;
    atom.model_index = model_index_;
    const std::string_view name_field = columns(line, 13, 16);
    atom.atom_name = std::string(trim_blanks(name_field));
    atom.alt_loc = line[16];
    // Column 21 is blank in the standard; some tools put a 4th residue-name character there.
    atom.residue_name = std::string(trim_blanks(columns(line, 18, 21)));
    atom.chain = std::string(trim_blanks(columns(line, 22, 22)));
    const std::string_view number_field = columns(line, 23, 26);
    if (trim_blanks(number_field).empty()) {
      atom.residue_number = kNoResidueNumber;
    } else if (auto number = parse_hybrid36(number_field, 4)) {
      atom.residue_number = *number;
    } else {
      fail(line_number, std::string(record_name(line)) + " record has a non-numeric residue number '" +
                            std::string(trim_blanks(number_field)) + "' (columns 23-26)");
    }
    atom.insertion_code = std::string(trim_blanks(columns(line, 27, 27)));
    atom.position = {coordinate(line, 31, "x", line_number), coordinate(line, 39, "y", line_number),
                     coordinate(line, 47, "z", line_number)};
    const std::string_view occupancy_field = columns(line, 55, 60);
    if (!trim_blanks(occupancy_field).empty()) {
      auto occupancy = parse_real(occupancy_field);
      if (!occupancy || !std::isfinite(*occupancy))
        fail(line_number, std::string(record_name(line)) + " record has a " + (occupancy ? "non-finite" : "non-numeric") +
                              " occupancy '" + std::string(trim_blanks(occupancy_field)) + "' (columns 55-60)");
      atom.occupancy = *occupancy;
    }
    const std::string element_column = normalize_element_symbol(columns(line, 77, 78));
    atom.element = element_column.empty() ? infer_element_from_pdb_atom_name(name_field) : element_column;
    result_.atoms.push_back(std::move(atom));
    atoms_in_model_ = true;
  }

  std::string_view text_;
  const std::string& file_;
  ParsedStructure result_;
  int model_index_ = 0;
  bool atoms_in_model_ = false;
  bool new_model_pending_ = false;
};

}  // namespace

ParsedStructure parse_pdb(std::string_view text, const std::string& file_name) {
  return PdbParser(text, file_name).run();
}

}  // namespace nano::structure
