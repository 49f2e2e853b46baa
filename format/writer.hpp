#pragma once
// Builds .nup packages from sections: lays them out 256-byte aligned after the header and table,
// compresses with zstd where that makes a section smaller, stores the mesh sections as Draco streams
// where asked (and, by default, where those are smaller), checksums everything.
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "format/layout.hpp"
#include "format/section_kind.hpp"

namespace nano::format {

// draco_if_smaller / draco apply to the four mesh sections (kDracoCodedKinds) together, which must
// then all ask the same and come with section "meshes": they are stored as one "draco_meshes"
// section if encode_draco_meshes can (values on its grids, canonical order) and, for
// draco_if_smaller, if that is smaller than zstd; otherwise as zstd_if_smaller.
enum class Compression { none, zstd_if_smaller, draco_if_smaller, draco };

struct SectionSource {
  std::uint32_t kind = 0;  // a SectionKind; any value is accepted so tests can write unknown kinds
  std::span<const std::byte> bytes;
  Compression compression = Compression::none;
  std::uint16_t flags = 0;
};

// The table's (format/section_table.hpp) choice for a kind: its flags column as entry flags, and
// zstd where smaller unless its codecs column says raw (the mesh kinds choose Draco only when asked).
constexpr std::uint16_t section_flags(SectionKind kind) { return static_cast<std::uint16_t>(section_info(kind).flags); }
constexpr Compression default_compression(SectionKind kind) {
  return section_info(kind).codecs == SectionCodecs::raw ? Compression::none : Compression::zstd_if_smaller;
}

template <class T>
SectionSource section_source(SectionKind kind, std::span<const T> records, Compression compression, std::uint16_t flags) {
  return {static_cast<std::uint32_t>(kind), std::as_bytes(records), compression, flags};
}
template <class T> SectionSource section_source(SectionKind kind, std::span<const T> records, Compression compression) {
  return section_source(kind, records, compression, section_flags(kind));
}
template <class T> SectionSource section_source(SectionKind kind, std::span<const T> records) {
  return section_source(kind, records, default_compression(kind));
}

inline constexpr int kDefaultZstdLevel = 9;

// What the section would take in the file stored as zstd_if_smaller.
std::uint64_t zstd_stored_size(std::span<const std::byte> raw, int zstd_level = kDefaultZstdLevel);

// The package bytes. Throws std::invalid_argument if a kind appears twice, a known kind's size is
// not a multiple of its record size or the mesh sections ask for Draco inconsistently: those are
// bugs of the caller, not bad input. Throws std::runtime_error naming why when Compression::draco
// was demanded and the meshes cannot be stored so.
std::vector<std::byte> build_package(std::span<const SectionSource> sections, int zstd_level = kDefaultZstdLevel);

// build_package written through nano::write_file_atomically.
void write_package(const std::filesystem::path& path, std::span<const SectionSource> sections,
                   int zstd_level = kDefaultZstdLevel);

}  // namespace nano::format
