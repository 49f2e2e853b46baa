#include "format/package_error.hpp"

#include "format/section_kind.hpp"

namespace nano::format {

const char* rule_name(Rule rule) {
  switch (rule) {
    case Rule::truncated: return "truncated";
    case Rule::bad_magic: return "bad-magic";
    case Rule::bad_endianness: return "bad-endianness";
    case Rule::unsupported_version: return "unsupported-version";
    case Rule::file_size_mismatch: return "file-size-mismatch";
    case Rule::header_checksum: return "header-checksum";
    case Rule::nonzero_reserved: return "nonzero-reserved";
    case Rule::table_bounds: return "table-bounds";
    case Rule::section_bounds: return "section-bounds";
    case Rule::misaligned: return "misaligned";
    case Rule::overlap: return "overlap";
    case Rule::nonzero_padding: return "nonzero-padding";
    case Rule::duplicate_section: return "duplicate-section";
    case Rule::unknown_codec: return "unknown-codec";
    case Rule::unknown_required_section: return "unknown-required-section";
    case Rule::record_size: return "record-size";
    case Rule::stored_checksum: return "stored-checksum";
    case Rule::raw_checksum: return "raw-checksum";
    case Rule::raw_size_limit: return "raw-size-limit";
    case Rule::decompression: return "decompression";
    case Rule::missing_section: return "missing-section";
    case Rule::index_out_of_range: return "index-out-of-range";
    case Rule::non_finite: return "non-finite";
    case Rule::inverted_aabb: return "inverted-aabb";
    case Rule::bad_value: return "bad-value";
    case Rule::mesh_codec: return "mesh-codec";
  }
  return "unknown-rule";
}

std::string describe(const Location& where) {
  std::string s;
  if (where.section_kind) s = "section " + section_kind_name(*where.section_kind) + ", ";
  s += where.decompressed ? "decompressed byte " : "byte ";
  return s + std::to_string(where.offset);
}

}  // namespace nano::format
