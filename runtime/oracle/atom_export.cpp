#include "runtime/oracle/atom_export.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>

#include "common/atomic_file.hpp"
#include "common/error.hpp"

namespace nano::oracle {
namespace {

// A NUL-padded fixed-width text field of AtomInfo, up to its first NUL.
template <std::size_t N> std::string field(const char (&text)[N]) { return {text, strnlen(text, N)}; }

struct AtomText {
  std::string chain, residue, atom, element;
  char alt = 0, insertion = 0;
  std::int32_t residue_number = 1;
};

AtomText text_of(const AtomSample& a, bool defaults) {
  AtomText t;
  if (a.info) {
    t.chain = field(a.info->chain);
    t.residue = field(a.info->residue_name);
    t.atom = field(a.info->atom_name);
    t.element = field(a.info->element);
    t.alt = a.info->alt_location;
    t.insertion = a.info->insertion_code;
    t.residue_number = a.info->residue_number;
  }
  // PDB and mmCIF need every identifier; CSV keeps "unknown" as empty.
  if (defaults) {
    if (t.chain.empty()) t.chain = "A";
    if (t.residue.empty()) t.residue = "UNK";
    if (t.atom.empty()) t.atom = "X";
  }
  return t;
}

class Writer {
public:
  explicit Writer(std::FILE* f) : f_(f) {}
  virtual ~Writer() = default;
  virtual void begin() {}
  virtual void atom(const AtomSample& a) = 0;
  virtual void end() {}

protected:
  std::FILE* f_;
};

class CsvWriter final : public Writer {
public:
  using Writer::Writer;
  void begin() override { std::fputs("copy,type,chain,residue,atom,element,x,y,z,radius,kind\n", f_); }
  void atom(const AtomSample& a) override {
    const AtomText t = text_of(a, false);
    static constexpr const char* kKinds[] = {"membrane", "core", "medium"};
    std::fprintf(f_, "%llu,%u,%s,%s,%s,%s,%.6f,%.6f,%.6f,%.6f,%s\n", static_cast<unsigned long long>(a.copy->number),
                 a.copy->molecule_type, quoted(t.chain).c_str(), quoted(t.residue).c_str(), quoted(t.atom).c_str(),
                 quoted(t.element).c_str(), a.position.x, a.position.y, a.position.z, a.radius,
                 kKinds[static_cast<int>(a.copy->id.kind)]);
  }

private:
  // RFC 4180: quote fields holding the separator, quotes or edge spaces; double inner quotes.
  static std::string quoted(const std::string& s) {
    if (s.find_first_of(",\"") == std::string::npos && (s.empty() || (s.front() != ' ' && s.back() != ' '))) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  }
};

bool is_polymer_residue(std::string_view r) {
  static constexpr std::array<std::string_view, 28> standard = {
      "ALA", "ARG", "ASN", "ASP", "CYS", "GLN", "GLU", "GLY", "HIS", "ILE", "LEU", "LYS", "MET", "PHE",
      "PRO", "SER", "THR", "TRP", "TYR", "VAL", "A",   "C",   "G",   "U",   "DA",  "DC",  "DG",  "DT"};
  return std::find(standard.begin(), standard.end(), r) != standard.end();
}

class PdbWriter final : public Writer {
public:
  PdbWriter(std::FILE* f, const std::filesystem::path& path) : Writer(f), path_(path) {}
  void begin() override {
    std::fputs("REMARK   1 WRITTEN BY NANOVIEW EXPORT: ONE CHAIN ID PER (COPY, SOURCE CHAIN), CYCLING\n"
               "REMARK   1 A-Z a-z 0-9; SOURCE CHAIN IN SEGID; B-FACTOR = ATOM RADIUS\n",
               f_);
  }
  void atom(const AtomSample& a) override {
    if (serial_ == kPdbMaxAtoms)
      throw InputError(path_.string(), "", "PDB holds at most 99,999 atoms and the box has more: write .cif instead, or use a smaller box");
    const AtomText t = text_of(a, true);
    if (!started_ || a.copy->number != copy_ || t.chain != chain_) {
      static constexpr char ids[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
      chain_id_ = ids[groups_++ % (sizeof ids - 1)];
      copy_ = a.copy->number;
      chain_ = t.chain;
      started_ = true;
    }
    for (int k = 0; k < 3; ++k)
      if (!(a.position[k] > -999.9995 && a.position[k] < 9999.9995))
        throw InputError(path_.string(), "", "coordinate " + std::to_string(a.position[k]) +
                                                  " does not fit PDB's 8.3 columns: write .cif instead");
    int number = t.residue_number;
    if (number < -999 || number > 9999) number = ((number % 10000) + 10000) % 10000;
    // Names shorter than 4 with a one-letter element start in column 14 (" CA "), by PDB convention.
    std::string name = t.atom.substr(0, 4);
    if (name.size() < 4 && t.element.size() <= 1) name = " " + name;
    const std::string residue = t.residue.size() <= 3 ? std::string(3 - t.residue.size(), ' ') + t.residue + " "
                                                      : t.residue.substr(0, 4);
    std::fprintf(f_, "%-6s%5llu %-4s%c%s%c%4d%c   %8.3f%8.3f%8.3f%6.2f%6.2f      %-4s%2s\n",
                 is_polymer_residue(t.residue) ? "ATOM" : "HETATM", static_cast<unsigned long long>(++serial_),
                 name.c_str(), a.info && t.alt ? t.alt : ' ', residue.c_str(), chain_id_, number,
                 t.insertion ? t.insertion : ' ', a.position.x, a.position.y, a.position.z, 1.0,
                 std::min(a.radius, 999.99), t.chain.substr(0, 4).c_str(), t.element.c_str());
  }
  void end() override { std::fputs("END\n", f_); }

private:
  std::filesystem::path path_;
  std::uint64_t serial_ = 0, groups_ = 0, copy_ = 0;
  bool started_ = false;
  std::string chain_;
  char chain_id_ = 'A';
};

class CifWriter final : public Writer {
public:
  using Writer::Writer;
  void begin() override {
    std::fputs("data_nanoview_export\n#\nloop_\n", f_);
    for (const char* tag : {"group_PDB", "id", "type_symbol", "label_atom_id", "label_alt_id", "label_comp_id",
                            "label_asym_id", "label_entity_id", "label_seq_id", "pdbx_PDB_ins_code", "Cartn_x",
                            "Cartn_y", "Cartn_z", "occupancy", "B_iso_or_equiv", "auth_seq_id", "auth_asym_id",
                            "pdbx_PDB_model_num"})
      std::fprintf(f_, "_atom_site.%s\n", tag);
  }
  void atom(const AtomSample& a) override {
    const AtomText t = text_of(a, true);
    const std::string asym = value(t.chain + "_" + std::to_string(a.copy->number));
    std::fprintf(f_, "%s %llu %s %s %s %s %s 1 . %s %.4f %.4f %.4f 1 %.4f %d %s 1\n",
                 is_polymer_residue(t.residue) ? "ATOM" : "HETATM", static_cast<unsigned long long>(++serial_),
                 value(t.element).c_str(), value(t.atom).c_str(), value(t.alt ? std::string(1, t.alt) : "").c_str(),
                 value(t.residue).c_str(), asym.c_str(), value(t.insertion ? std::string(1, t.insertion) : "").c_str(),
                 a.position.x, a.position.y, a.position.z, a.radius, t.residue_number, asym.c_str());
  }
  void end() override { std::fputs("#\n", f_); }

private:
  // A CIF token: '.' for none; quoted when it holds blanks or starts like syntax.
  static std::string value(const std::string& s) {
    if (s.empty()) return ".";
    const bool plain = s.find_first_of(" \t'\"") == std::string::npos && std::string_view("_#$;[]").find(s[0]) == std::string_view::npos &&
                       s != "." && s != "?";
    if (plain) return s;
    const char q = s.find('\'') == std::string::npos ? '\'' : '"';
    return q + s + q;
  }
  std::uint64_t serial_ = 0;
};

std::unique_ptr<Writer> make_writer(AtomFormat format, std::FILE* f, const std::filesystem::path& path) {
  switch (format) {
    case AtomFormat::csv: return std::make_unique<CsvWriter>(f);
    case AtomFormat::pdb: return std::make_unique<PdbWriter>(f, path);
    case AtomFormat::mmcif: return std::make_unique<CifWriter>(f);
  }
  return nullptr;
}

}  // namespace

AtomFormat atom_format_of(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".csv") return AtomFormat::csv;
  if (ext == ".pdb") return AtomFormat::pdb;
  if (ext == ".cif" || ext == ".mmcif") return AtomFormat::mmcif;
  throw InputError(path.string(), "", "unknown output format '" + ext + "': use .csv, .pdb or .cif");
}

ExportCounts export_atoms(const ExplicitScene& scene, const WorldBox& box, const std::filesystem::path& path,
                          AtomFormat format) {
  ExportCounts counts;
  write_file_atomically(path, [&](std::FILE* f) {
    counts = {};
    const std::unique_ptr<Writer> writer = make_writer(format, f, path);
    writer->begin();
    std::uint64_t last = 0;
    scene.for_each_atom(box, [&](const AtomSample& a) {
      // Atoms of a copy arrive together and each copy once, so a new number is a new copy.
      if (counts.atoms == 0 || a.copy->number != last) ++counts.copies;
      last = a.copy->number;
      ++counts.atoms;
      writer->atom(a);
    });
    writer->end();
  });
  return counts;
}

}  // namespace nano::oracle
