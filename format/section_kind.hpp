#pragma once
// The section kinds of a .nup package, their names, record types and per-kind rules, all derived
// from the one list in format/section_table.hpp.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "format/layout.hpp"
#include "format/records.hpp"
#include "format/section_table.hpp"

namespace nano::format {

// Values are part of the file format: never renumber, only append (see docs/format.md).
enum class SectionKind : std::uint32_t {
#define NANO_SECTION_ENUM(name, value, ...) name = value,
  NANO_SECTION_TABLE(NANO_SECTION_ENUM)
#undef NANO_SECTION_ENUM
};

// Every kind this reader knows, in numeric order.
inline constexpr SectionKind kAllSectionKinds[] = {
#define NANO_SECTION_KIND(name, ...) SectionKind::name,
    NANO_SECTION_TABLE(NANO_SECTION_KIND)
#undef NANO_SECTION_KIND
};

// The record type of each kind, so Package::records<K>() hands out a span of the right type.
template <SectionKind K> struct RecordOf;
#define NANO_SECTION_RECORD(name, value, record, ...) \
  template <> struct RecordOf<SectionKind::name> { using type = record; };
NANO_SECTION_TABLE(NANO_SECTION_RECORD)
#undef NANO_SECTION_RECORD
template <SectionKind K> using record_t = typename RecordOf<K>::type;

// The table's flags, since and codecs columns (section_table.hpp).
enum class SectionFlags : std::uint16_t { optional = 0, required = 1 };  // 1 = kSectionRequired
enum class SectionCodecs : std::uint8_t { zstd, mesh, raw };
static_assert(static_cast<std::uint16_t>(SectionFlags::required) == kSectionRequired);

// The sections that must be present when a section has records (the table's needs column).
struct SectionNeeds {
  std::array<SectionKind, 6> kinds{};
  std::size_t count = 0;
  constexpr const SectionKind* begin() const { return kinds.data(); }
  constexpr const SectionKind* end() const { return kinds.data() + count; }
};

// One row of the table as data.
struct SectionInfo {
  SectionKind kind;
  std::string_view name;
  std::string_view record_type;  // as spelled in the table, e.g. "gpu::MoleculeType"
  std::uint64_t record_size;
  std::size_t record_alignment;
  SectionFlags flags;
  std::uint16_t since_minor;
  SectionCodecs codecs;
  std::string_view rule;  // the name of the validator's rule function
  SectionNeeds needs;
  std::string_view content;
};

namespace section_table_detail {
template <class... K> constexpr SectionNeeds needs(K... k) {
  static_assert(sizeof...(K) <= 6, "SectionNeeds holds six kinds");
  return {{k...}, sizeof...(K)};
}
}  // namespace section_table_detail

// The table in value order: kSectionTable[value - 1] is the row of kind `value`.
inline constexpr std::array kSectionTable = [] {
  using enum SectionKind;
  using enum SectionFlags;
  using enum SectionCodecs;
  using section_table_detail::needs;
#define NANO_SECTION_INFO(name_, value, record, flags_, since, codecs_, rule_, needs_, content_)                   \
  SectionInfo{SectionKind::name_, #name_, #record, sizeof(record), alignof(record), flags_, since, codecs_, #rule_, \
              needs needs_, content_},
  return std::array{NANO_SECTION_TABLE(NANO_SECTION_INFO)};
#undef NANO_SECTION_INFO
}();

namespace section_table_detail {
constexpr bool rows_are_well_formed() {
  for (std::size_t i = 0; i < kSectionTable.size(); ++i) {
    const SectionInfo& row = kSectionTable[i];
    if (static_cast<std::uint32_t>(row.kind) != i + 1) return false;  // values 1, 2, ... in row order
    if (row.since_minor > kVersionMinor) return false;                  // a new kind needs a new minor
    if (row.record_alignment > kSectionAlignment || row.record_size % row.record_alignment != 0) return false;
  }
  return true;
}
static_assert(rows_are_well_formed(),
              "section_table.hpp: rows are in value order from 1 without gaps, since <= kVersionMinor, records "
              "aligned within a section's 256 bytes");
}  // namespace section_table_detail

constexpr const SectionInfo& section_info(SectionKind kind) { return kSectionTable[static_cast<std::uint32_t>(kind) - 1]; }
constexpr bool is_known_section_kind(std::uint32_t kind) { return kind >= 1 && kind <= kSectionTable.size(); }
// "molecules", or "kind 4711" for a kind this reader does not know.
std::string section_kind_name(std::uint32_t kind);
inline std::string section_kind_name(SectionKind kind) { return section_kind_name(static_cast<std::uint32_t>(kind)); }
std::optional<SectionKind> section_kind_from_name(std::string_view name);
// Size of one record of the kind (1 for byte sections such as strings, occupancy and provenance).
constexpr std::uint64_t record_size(SectionKind kind) {
  return is_known_section_kind(static_cast<std::uint32_t>(kind)) ? section_info(kind).record_size : 1;
}
// Whether codec draco may store the kind (the table's codecs column says mesh).
constexpr bool is_draco_coded_kind(std::uint32_t kind) {
  return is_known_section_kind(kind) && kSectionTable[kind - 1].codecs == SectionCodecs::mesh;
}

}  // namespace nano::format
