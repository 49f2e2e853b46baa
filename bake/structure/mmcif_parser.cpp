#include "bake/structure/mmcif_parser.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <vector>

#include "bake/structure/cif_tokenizer.hpp"
#include "bake/structure/element.hpp"
#include "bake/structure/field_parsing.hpp"
#include "common/error.hpp"

namespace nano::structure {
namespace {

constexpr std::string_view kAtomSitePrefix = "_atom_site.";

enum Column : int {
  kGroup, kX, kY, kZ, kOccupancy, kTypeSymbol, kAltId, kInsCode, kModel,
  kAuthAtom, kLabelAtom, kAuthComp, kLabelComp, kAuthAsym, kLabelAsym, kAuthSeq, kLabelSeq,
  kColumnCount
};

constexpr std::array<std::string_view, kColumnCount> kColumnNames = {
    "group_pdb", "cartn_x", "cartn_y", "cartn_z", "occupancy", "type_symbol", "label_alt_id",
    "pdbx_pdb_ins_code", "pdbx_pdb_model_num", "auth_atom_id", "label_atom_id", "auth_comp_id",
    "label_comp_id", "auth_asym_id", "label_asym_id", "auth_seq_id", "label_seq_id"};

bool is_value(CifTokenKind kind) {
  return kind == CifTokenKind::Value || kind == CifTokenKind::Inapplicable || kind == CifTokenKind::Unknown;
}

std::string lowercase(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool is_atom_site_tag(std::string_view tag) {
  return tag.size() > kAtomSitePrefix.size() && lowercase(tag.substr(0, kAtomSitePrefix.size())) == kAtomSitePrefix;
}

// Maps each known _atom_site item to its position in a row (-1 when the file lacks it).
class AtomSiteLayout {
public:
  // Items of other categories in the same loop (not valid mmCIF, but not worth refusing) are not ours.
  void add(std::string_view tag, int position) {
    if (!is_atom_site_tag(tag)) return;
    const std::string item = lowercase(tag.substr(kAtomSitePrefix.size()));
    for (int c = 0; c < kColumnCount; ++c)
      if (kColumnNames[c] == item && index_[c] < 0) index_[c] = position;
  }
  int operator[](Column c) const { return index_[c]; }

private:
  std::array<int, kColumnCount> index_ = [] {
    std::array<int, kColumnCount> a;
    a.fill(-1);
    return a;
  }();
};

class MmcifParser {
public:
  MmcifParser(std::string_view text, const std::string& file) : tokens_(text, file), file_(file) {}

  ParsedStructure run() {
    CifToken token = tokens_.next();
    if (token.kind != CifTokenKind::DataBlock) {
      if (token.kind == CifTokenKind::End) throw InputError(file_, "whole file", "no data_ block: not an mmCIF file");
      fail(token.line, "CIF content before the first data_ block header");
    }
    block_name_ = std::string(token.text);
    token = tokens_.next();
    std::vector<std::string_view> pair_tags;
    std::vector<CifToken> pair_values;
    std::size_t pair_line = 0;
    while (token.kind != CifTokenKind::End && token.kind != CifTokenKind::DataBlock) {
      switch (token.kind) {
        case CifTokenKind::Loop: token = loop(token.line); continue;
        case CifTokenKind::Tag: {
          const CifToken value = tokens_.next();
          if (!is_value(value.kind)) fail(token.line, "tag " + std::string(token.text) + " has no value");
          if (is_atom_site_tag(token.text)) {
            if (pair_tags.empty()) pair_line = token.line;
            pair_tags.push_back(token.text);
            pair_values.push_back(value);
          }
          break;
        }
        case CifTokenKind::Save: break;
        default: fail(token.line, "value '" + std::string(token.text) + "' has no tag (expected a tag or loop_)");
      }
      token = tokens_.next();
    }
    // A structure with a single atom may write _atom_site as tag-value pairs instead of a loop.
    if (!atom_site_seen_ && !pair_tags.empty()) {
      AtomSiteLayout layout;
      for (std::size_t i = 0; i < pair_tags.size(); ++i) layout.add(pair_tags[i], static_cast<int>(i));
      require_columns(layout, pair_line);
      add_atom(layout, pair_values);
      atom_site_seen_ = true;
    }
    if (!atom_site_seen_) throw InputError(file_, "data_" + block_name_, "no _atom_site category: the first data block holds no atoms");
    if (result_.atoms.empty()) throw InputError(file_, "data_" + block_name_, "the _atom_site loop has no rows: no atoms");
    result_.model_count = static_cast<int>(model_numbers_.size());
    return std::move(result_);
  }

private:
  [[noreturn]] void fail(std::size_t line, const std::string& rule) const {
    throw InputError(file_, "line " + std::to_string(line), rule);
  }

  // Reads a loop's header and values; returns the first token after the loop.
  CifToken loop(std::size_t loop_line) {
    std::vector<std::string_view> tags;
    CifToken token = tokens_.next();
    while (token.kind == CifTokenKind::Tag) {
      tags.push_back(token.text);
      token = tokens_.next();
    }
    if (tags.empty()) fail(loop_line, "loop_ has no tags");
    const bool atom_site = !atom_site_seen_ && is_atom_site_tag(tags.front());
    AtomSiteLayout layout;
    if (atom_site) {
      for (std::size_t i = 0; i < tags.size(); ++i) layout.add(tags[i], static_cast<int>(i));
      require_columns(layout, loop_line);
      atom_site_seen_ = true;
    }
    std::vector<CifToken> row;
    row.reserve(tags.size());
    std::size_t value_count = 0;
    while (is_value(token.kind)) {
      ++value_count;
      if (atom_site) {
        row.push_back(token);
        if (row.size() == tags.size()) {
          add_atom(layout, row);
          row.clear();
        }
      }
      token = tokens_.next();
    }
    if (value_count % tags.size() != 0)
      fail(loop_line, "loop_ has " + std::to_string(value_count) + " values, not a multiple of its " +
                          std::to_string(tags.size()) + " columns (truncated or garbled loop)");
    return token;
  }

  void require_columns(const AtomSiteLayout& layout, std::size_t line) const {
    for (Column c : {kX, kY, kZ})
      if (layout[c] < 0) fail(line, "_atom_site has no Cartn_" + std::string(1, "xyz"[c - kX]) + " column");
    if (layout[kAuthAtom] < 0 && layout[kLabelAtom] < 0)
      fail(line, "_atom_site has neither an auth_atom_id nor a label_atom_id column");
  }

  static bool present(const std::vector<CifToken>& row, int index) {
    return index >= 0 && row[index].kind == CifTokenKind::Value && !row[index].text.empty();
  }

  // The author item when given, else the label item; "" when neither holds a value.
  static std::string_view preferred(const std::vector<CifToken>& row, int author, int label) {
    if (present(row, author)) return row[author].text;
    if (present(row, label)) return row[label].text;
    return {};
  }

  double real(const std::vector<CifToken>& row, int index, std::string_view item) const {
    const CifToken& token = row[index];
    std::string_view text = token.text;
    // Drop a standard uncertainty such as "12.345(3)".
    if (const auto paren = text.find('('); paren != std::string_view::npos && text.back() == ')') text = text.substr(0, paren);
    const auto value = token.kind == CifTokenKind::Value ? parse_real(text) : std::nullopt;
    if (value && std::isfinite(*value)) return *value;
    fail(token.line, "_atom_site." + std::string(item) + " has a " + (value ? "non-finite" : "non-numeric") + " value '" +
                         std::string(token.text) + "'");
  }

  double coordinate(const std::vector<CifToken>& row, int index, std::string_view item) const {
    const double value = real(row, index, item);
    if (std::abs(value) > kMaxCoordinate)
      fail(row[index].line, "_atom_site." + std::string(item) + " has a far-off value '" + std::string(row[index].text) +
                                "' (beyond ±1e6 Å)");
    return value;
  }

  int model_index(const std::vector<CifToken>& row, int index) {
    int number = 1;
    if (present(row, index)) {
      auto parsed = parse_integer(row[index].text);
      if (!parsed) fail(row[index].line, "_atom_site.pdbx_PDB_model_num has a non-integer value '" + std::string(row[index].text) + "'");
      number = *parsed;
    }
    if (!model_numbers_.empty() && model_numbers_[last_model_] == number) return static_cast<int>(last_model_);
    const auto found = std::find(model_numbers_.begin(), model_numbers_.end(), number);
    last_model_ = static_cast<std::size_t>(found - model_numbers_.begin());
    if (found == model_numbers_.end()) model_numbers_.push_back(number);
    return static_cast<int>(last_model_);
  }

  void add_atom(const AtomSiteLayout& layout, const std::vector<CifToken>& row) {
    Atom atom;
    atom.line = row.front().line;
    atom.position = {coordinate(row, layout[kX], "Cartn_x"), coordinate(row, layout[kY], "Cartn_y"),
                     coordinate(row, layout[kZ], "Cartn_z")};
    if (present(row, layout[kOccupancy])) atom.occupancy = real(row, layout[kOccupancy], "occupancy");
    atom.atom_name = std::string(preferred(row, layout[kAuthAtom], layout[kLabelAtom]));
    atom.residue_name = std::string(preferred(row, layout[kAuthComp], layout[kLabelComp]));
    atom.chain = std::string(preferred(row, layout[kAuthAsym], layout[kLabelAsym]));
    const int seq_author = layout[kAuthSeq], seq_label = layout[kLabelSeq];
    const int seq_index = present(row, seq_author) ? seq_author : present(row, seq_label) ? seq_label : -1;
    if (seq_index >= 0) {
      auto number = parse_integer(row[seq_index].text);
      if (!number)
        fail(row[seq_index].line, "_atom_site residue number has a non-integer value '" + std::string(row[seq_index].text) + "'");
      atom.residue_number = *number;
    }
    if (present(row, layout[kInsCode])) atom.insertion_code = std::string(row[layout[kInsCode]].text);
    if (present(row, layout[kAltId])) atom.alt_loc = row[layout[kAltId]].text.front();
    atom.hetatm = present(row, layout[kGroup]) && row[layout[kGroup]].text == "HETATM";
    atom.model_index = model_index(row, layout[kModel]);
    atom.element = present(row, layout[kTypeSymbol]) ? normalize_element_symbol(row[layout[kTypeSymbol]].text)
                                                     : infer_element_from_atom_name(atom.atom_name, atom.residue_name);
    result_.atoms.push_back(std::move(atom));
  }

  CifTokenizer tokens_;
  const std::string& file_;
  std::string block_name_;
  ParsedStructure result_;
  bool atom_site_seen_ = false;
  std::vector<int> model_numbers_;  // distinct pdbx_PDB_model_num values in order of appearance
  std::size_t last_model_ = 0;
};

}  // namespace

ParsedStructure parse_mmcif(std::string_view text, const std::string& file_name) {
  return MmcifParser(text, file_name).run();
}

}  // namespace nano::structure
