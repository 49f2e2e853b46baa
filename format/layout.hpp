#pragma once
// The byte layout of the .nup container: header, section table, constants and checksums.
// Fields are serialized one by one, little-endian, so no compiler padding ever reaches the file.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace nano::format {

inline constexpr std::array<unsigned char, 8> kMagic = {0x89, 'N', 'U', 'P', '\r', '\n', 0x1a, '\n'};
inline constexpr std::uint16_t kVersionMajor = 2;
inline constexpr std::uint16_t kVersionMinor = 9;
// Written little-endian it reads 04 03 02 01; a big-endian writer would produce 01 02 03 04.
inline constexpr std::uint32_t kEndianMark = 0x01020304u;
inline constexpr std::uint64_t kHeaderSize = 64;
inline constexpr std::uint64_t kEntrySize = 48;
inline constexpr std::uint64_t kSectionAlignment = 256;
inline constexpr std::uint32_t kMaxSections = 4096;
// Caps on what a section may claim to decompress to, checked before anything is allocated.
inline constexpr std::uint64_t kMaxRawSectionBytes = std::uint64_t{1} << 36;  // 64 GiB
// A zstd block yields at most 128 KiB and costs at least 4 bytes, so no honest frame expands more.
inline constexpr std::uint64_t kMaxZstdExpansion = 32768;

// draco (format 2.6): the four mesh sections hold no bytes of their own; their raw bytes are decoded
// from section "draco_meshes" (format/draco_mesh_sections.hpp), all four together.
enum class Codec : std::uint16_t { none = 0, zstd = 1, draco = 2 };
// Section flag: a reader that does not know the kind must refuse the package.
inline constexpr std::uint16_t kSectionRequired = 1;
inline constexpr std::uint16_t kKnownSectionFlags = kSectionRequired;

struct Header {
  std::uint16_t version_major = kVersionMajor;
  std::uint16_t version_minor = kVersionMinor;
  std::uint32_t endian_mark = kEndianMark;
  std::uint64_t file_size = 0;
  std::uint64_t table_offset = kHeaderSize;
  std::uint32_t section_count = 0;
  std::uint32_t flags = 0;
  std::uint64_t reserved0 = 0;
  std::uint64_t reserved1 = 0;
  std::uint64_t checksum = 0;  // XXH3-64 of header bytes [0, 56) followed by the whole table
};

// Byte offsets of the header fields (docs/format.md has the same table).
namespace header_offset {
inline constexpr std::size_t magic = 0, version_major = 8, version_minor = 10, endian_mark = 12,
                             file_size = 16, table_offset = 24, section_count = 32, flags = 36,
                             reserved0 = 40, reserved1 = 48, checksum = 56;
}

struct SectionEntry {
  std::uint32_t kind = 0;
  std::uint16_t codec = 0;
  std::uint16_t flags = 0;
  std::uint64_t offset = 0;
  std::uint64_t stored_size = 0;
  std::uint64_t raw_size = 0;
  std::uint64_t stored_checksum = 0;  // XXH3-64 of the stored bytes
  std::uint64_t raw_checksum = 0;     // XXH3-64 of the decompressed bytes (zstd), 0 for codec none
};

namespace entry_offset {
inline constexpr std::size_t kind = 0, codec = 4, flags = 6, offset = 8, stored_size = 16,
                             raw_size = 24, stored_checksum = 32, raw_checksum = 40;
}

void encode_header(const Header& header, std::span<std::byte, kHeaderSize> out);  // magic included
Header decode_header(std::span<const std::byte, kHeaderSize> in);                 // no checks
void encode_section_entry(const SectionEntry& entry, std::span<std::byte, kEntrySize> out);
SectionEntry decode_section_entry(std::span<const std::byte, kEntrySize> in);

std::uint64_t xxh3(std::span<const std::byte> bytes);
std::uint64_t header_checksum(std::span<const std::byte, kHeaderSize> header, std::span<const std::byte> table);
// Recomputes and stores the header checksum of a package whose header and table are otherwise
// final. Throws std::out_of_range if the header's table does not lie inside `package`.
void seal_header(std::span<std::byte> package);

inline constexpr std::uint64_t align_up(std::uint64_t v, std::uint64_t a) { return (v + a - 1) / a * a; }

}  // namespace nano::format
