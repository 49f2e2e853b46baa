#pragma once
// Why a package was rejected: a machine-checkable rule code plus where (section kind and byte
// offset). The message still reads "FILE:WHERE: RULE" as for every other nano::InputError.
#include <cstdint>
#include <optional>
#include <string>

#include "common/error.hpp"

namespace nano::format {

enum class Rule {
  truncated,              // file shorter than the header, a table or a section claims
  bad_magic,
  bad_endianness,
  unsupported_version,    // another major version
  file_size_mismatch,     // header's file size differs from the actual size
  header_checksum,        // header + table checksum
  nonzero_reserved,       // reserved header/table field or record member not zero, unknown flag bit
  table_bounds,           // table outside the file, overlapping the header, too many sections
  section_bounds,         // section outside the file or over the header/table (offset+size overflow included)
  misaligned,             // section offset not a multiple of 256
  overlap,                // two sections share bytes
  nonzero_padding,        // a byte outside header, table and sections is not zero
  duplicate_section,
  unknown_codec,
  unknown_required_section,
  record_size,            // size not a multiple of the record size, or wrong record count
  stored_checksum,
  raw_checksum,
  raw_size_limit,         // claimed raw size beyond the documented caps
  decompression,          // not exactly one valid zstd frame whose content size equals raw size
  missing_section,        // a section referenced by another one is absent
  index_out_of_range,
  non_finite,
  inverted_aabb,
  bad_value,              // a value outside its documented domain
  mesh_codec,             // codec draco on a section it cannot serve, or on some mesh sections but not all
};

// "index-out-of-range" etc.: stable names used in messages and in `nanoview validate --json`.
const char* rule_name(Rule rule);

// Where a problem is: the section (if any) and a byte offset, either in the file or, for a
// zstd section, in its decompressed bytes.
struct Location {
  std::optional<std::uint32_t> section_kind;
  std::uint64_t offset = 0;
  bool decompressed = false;
};

std::string describe(const Location& where);

class PackageError : public InputError {
public:
  PackageError(std::string file, Rule rule, Location where, const std::string& detail)
      : InputError(std::move(file), describe(where), std::string(rule_name(rule)) + ": " + detail),
        code_(rule), location_(where) {}
  Rule code() const { return code_; }
  const Location& location() const { return location_; }

private:
  Rule code_;
  Location location_;
};

}  // namespace nano::format
