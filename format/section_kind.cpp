#include "format/section_kind.hpp"

namespace nano::format {

std::string section_kind_name(std::uint32_t kind) {
  if (is_known_section_kind(kind)) return std::string(kSectionTable[kind - 1].name);
  return "kind " + std::to_string(kind);
}

std::optional<SectionKind> section_kind_from_name(std::string_view name) {
  for (const SectionInfo& row : kSectionTable)
    if (row.name == name) return row.kind;
  return std::nullopt;
}

}  // namespace nano::format
