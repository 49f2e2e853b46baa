#pragma once
// Builds .nup packages from sections: lays them out 256-byte aligned after the header and table,
// compresses with zstd where that makes a section smaller, checksums everything.
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "format/layout.hpp"
#include "format/section_kind.hpp"

namespace nano::format {

enum class Compression { none, zstd_if_smaller };

struct SectionSource {
  std::uint32_t kind = 0;  // a SectionKind; any value is accepted so tests can write unknown kinds
  std::span<const std::byte> bytes;
  Compression compression = Compression::none;
  std::uint16_t flags = 0;
};

template <class T>
SectionSource section_source(SectionKind kind, std::span<const T> records,
                             Compression compression = Compression::zstd_if_smaller, std::uint16_t flags = 0) {
  return {static_cast<std::uint32_t>(kind), std::as_bytes(records), compression, flags};
}

inline constexpr int kDefaultZstdLevel = 9;

// The package bytes. Throws std::invalid_argument if a kind appears twice or a known kind's size
// is not a multiple of its record size: those are bugs of the caller, not bad input.
std::vector<std::byte> build_package(std::span<const SectionSource> sections, int zstd_level = kDefaultZstdLevel);

// build_package written through nano::write_file_atomically.
void write_package(const std::filesystem::path& path, std::span<const SectionSource> sections,
                   int zstd_level = kDefaultZstdLevel);

}  // namespace nano::format
