// Prints the section table of docs/format.md from format/section_table.hpp, or checks (--check) or
// rewrites (--update) the part of a document between the markers below. The test
// format.docs_section_table runs --check on docs/format.md.
//   section_table_doc                      print the table
//   section_table_doc --check FILE         exit 1, with a hint, if FILE's table differs
//   section_table_doc --update FILE        replace FILE's table
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <string_view>

#include "format/layout.hpp"
#include "format/section_kind.hpp"

namespace {

using namespace nano::format;

constexpr std::string_view kBegin = "<!-- BEGIN section table: generated from format/section_table.hpp by section_table_doc -->\n";
constexpr std::string_view kEnd = "<!-- END section table -->\n";

std::string record_label(const SectionInfo& row) {
  const std::string size = std::to_string(row.record_size);
  const std::string_view type = row.record_type;
  if (type == "char") return "bytes (" + size + ")";
  if (type == "std::uint8_t") return "u8 (" + size + ")";
  if (type == "std::uint32_t") return "u32 (" + size + ")";
  if (type.starts_with("glm::")) return std::string(type.substr(5)) + " (" + size + ")";
  if (type.starts_with("gpu::")) return std::string(type.substr(5)) + " (" + size + ", GPU)";
  return std::string(type) + " (" + size + ", CPU)";
}

std::string codecs_label(SectionCodecs c) {
  switch (c) {
  case SectionCodecs::zstd: return "none, zstd";
  case SectionCodecs::mesh: return "none, zstd, draco";
  case SectionCodecs::raw: return "none, zstd (written: none)";
  }
  return "?";
}

std::string table() {
  std::ostringstream out;
  out << "| kind | name | record (size) | since | flags | codecs | needs | rule | content and rules |\n"
      << "|---|---|---|---|---|---|---|---|---|\n";
  for (const SectionInfo& row : kSectionTable) {
    std::string needs;
    for (const SectionKind k : row.needs) needs += (needs.empty() ? "" : ", ") + section_kind_name(k);
    out << "| " << static_cast<std::uint32_t>(row.kind) << " | " << row.name << " | " << record_label(row) << " | "
        << kVersionMajor << "." << row.since_minor << " | " << (row.flags == SectionFlags::required ? "required" : "")
        << " | " << codecs_label(row.codecs) << " | " << needs << " | "
        << (row.rule == "no_rule_of_its_own" ? std::string("—") : "`" + std::string(row.rule) + "`") << " | "
        << row.content << " |\n";
  }
  return out.str();
}

int usage() {
  std::cerr << "usage: section_table_doc [--check FILE | --update FILE]\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 1) {
    std::cout << table();
    return 0;
  }
  if (argc != 3) return usage();
  const std::string mode = argv[1], path = argv[2];
  if (mode != "--check" && mode != "--update") return usage();
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::cerr << "section_table_doc: cannot read " << path << "\n";
    return 2;
  }
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t begin = doc.find(kBegin), end = doc.find(kEnd);
  if (begin == std::string::npos || end == std::string::npos || end < begin) {
    std::cerr << "section_table_doc: " << path << " lacks the markers\n  " << kBegin << "  " << kEnd;
    return 2;
  }
  const std::size_t from = begin + kBegin.size();
  const std::string expected = table();
  if (doc.compare(from, end - from, expected) == 0) return 0;
  if (mode == "--check") {
    std::cerr << "section_table_doc: the section table in " << path
              << " differs from format/section_table.hpp; run\n  section_table_doc --update " << path << "\n";
    return 1;
  }
  std::ofstream(path, std::ios::binary) << doc.substr(0, from) << expected << doc.substr(end);
  return 0;
}
