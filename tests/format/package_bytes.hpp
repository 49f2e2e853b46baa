#pragma once
// Test-side access to package bytes at the documented offsets (docs/format.md), written
// independently of format/layout.cpp so the tests check the layout instead of echoing it.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "format/package.hpp"
#include "format/validator.hpp"

namespace nano::format::test {

inline std::uint64_t get_le(std::span<const std::byte> b, std::size_t at, int width) {
  std::uint64_t v = 0;
  for (int i = 0; i < width; ++i) v |= std::uint64_t(std::to_integer<unsigned>(b[at + i])) << (8 * i);
  return v;
}

inline void put_le(std::span<std::byte> b, std::size_t at, int width, std::uint64_t v) {
  for (int i = 0; i < width; ++i) b[at + i] = std::byte((v >> (8 * i)) & 0xff);
}

// Header fields and entry fields as (offset, width), from the format document.
struct Field {
  const char* name;
  std::size_t offset;
  int width;
};
inline constexpr Field kHeaderFields[] = {{"version_major", 8, 2},  {"version_minor", 10, 2}, {"endian_mark", 12, 4},
                                          {"file_size", 16, 8},     {"table_offset", 24, 8},  {"section_count", 32, 4},
                                          {"flags", 36, 4},         {"reserved0", 40, 8},     {"reserved1", 48, 8},
                                          {"checksum", 56, 8}};
inline constexpr Field kEntryFields[] = {{"kind", 0, 4},         {"codec", 4, 2},        {"flags", 6, 2},
                                         {"offset", 8, 8},       {"stored_size", 16, 8}, {"raw_size", 24, 8},
                                         {"stored_checksum", 32, 8}, {"raw_checksum", 40, 8}};
inline constexpr std::size_t kTableAt = 64, kEntryBytes = 48;

inline std::size_t entry_at(std::size_t index) { return kTableAt + index * kEntryBytes; }

// The table index of the entry of `kind` in a package built by the writer.
inline std::size_t entry_index(std::span<const std::byte> b, SectionKind kind) {
  const std::size_t count = get_le(b, 32, 4);
  for (std::size_t i = 0; i < count; ++i)
    if (get_le(b, entry_at(i), 4) == static_cast<std::uint32_t>(kind)) return i;
  return SIZE_MAX;
}

// A patched package with every stored checksum and the header checksum made to agree again, so that
// the lie reaches the checks behind them.
inline std::vector<std::byte> resealed(std::vector<std::byte> b) {
  const std::size_t count = get_le(b, 32, 4);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t at = entry_at(i);
    const std::span<const std::byte> stored(b.data() + get_le(b, at + 8, 8), get_le(b, at + 16, 8));
    put_le(b, at + 32, 8, xxh3(stored));
  }
  seal_header(b);
  return b;
}

// The rule a package breaks, or nullopt if it opens and validates.
inline std::optional<Rule> broken_rule(std::span<const std::byte> bytes) {
  try {
    const Package p = Package::from_bytes(bytes, "test.nup");
    validate_semantics(p);
    return std::nullopt;
  } catch (const PackageError& e) {
    return e.code();
  }
}

}  // namespace nano::format::test
