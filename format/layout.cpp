#include "format/layout.hpp"

#include <cstring>
#include <stdexcept>
#define XXH_STATIC_LINKING_ONLY  // XXH3_state_t on the stack
#include <xxhash.h>

#include "format/checked_math.hpp"

namespace nano::format {
namespace {

template <class T> void put(std::span<std::byte> out, std::size_t at, T value) {
  for (std::size_t i = 0; i < sizeof(T); ++i)
    out[at + i] = static_cast<std::byte>((static_cast<std::uint64_t>(value) >> (8 * i)) & 0xff);
}

template <class T> T get(std::span<const std::byte> in, std::size_t at) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) v |= std::uint64_t(std::to_integer<unsigned>(in[at + i])) << (8 * i);
  return static_cast<T>(v);
}

}  // namespace

void encode_header(const Header& h, std::span<std::byte, kHeaderSize> out) {
  std::memcpy(out.data(), kMagic.data(), kMagic.size());
  namespace o = header_offset;
  put(out, o::version_major, h.version_major);
  put(out, o::version_minor, h.version_minor);
  put(out, o::endian_mark, h.endian_mark);
  put(out, o::file_size, h.file_size);
  put(out, o::table_offset, h.table_offset);
  put(out, o::section_count, h.section_count);
  put(out, o::flags, h.flags);
  put(out, o::reserved0, h.reserved0);
  put(out, o::reserved1, h.reserved1);
  put(out, o::checksum, h.checksum);
}

Header decode_header(std::span<const std::byte, kHeaderSize> in) {
  namespace o = header_offset;
  Header h;
  h.version_major = get<std::uint16_t>(in, o::version_major);
  h.version_minor = get<std::uint16_t>(in, o::version_minor);
  h.endian_mark = get<std::uint32_t>(in, o::endian_mark);
  h.file_size = get<std::uint64_t>(in, o::file_size);
  h.table_offset = get<std::uint64_t>(in, o::table_offset);
  h.section_count = get<std::uint32_t>(in, o::section_count);
  h.flags = get<std::uint32_t>(in, o::flags);
  h.reserved0 = get<std::uint64_t>(in, o::reserved0);
  h.reserved1 = get<std::uint64_t>(in, o::reserved1);
  h.checksum = get<std::uint64_t>(in, o::checksum);
  return h;
}

void encode_section_entry(const SectionEntry& e, std::span<std::byte, kEntrySize> out) {
  namespace o = entry_offset;
  put(out, o::kind, e.kind);
  put(out, o::codec, e.codec);
  put(out, o::flags, e.flags);
  put(out, o::offset, e.offset);
  put(out, o::stored_size, e.stored_size);
  put(out, o::raw_size, e.raw_size);
  put(out, o::stored_checksum, e.stored_checksum);
  put(out, o::raw_checksum, e.raw_checksum);
}

SectionEntry decode_section_entry(std::span<const std::byte, kEntrySize> in) {
  namespace o = entry_offset;
  SectionEntry e;
  e.kind = get<std::uint32_t>(in, o::kind);
  e.codec = get<std::uint16_t>(in, o::codec);
  e.flags = get<std::uint16_t>(in, o::flags);
  e.offset = get<std::uint64_t>(in, o::offset);
  e.stored_size = get<std::uint64_t>(in, o::stored_size);
  e.raw_size = get<std::uint64_t>(in, o::raw_size);
  e.stored_checksum = get<std::uint64_t>(in, o::stored_checksum);
  e.raw_checksum = get<std::uint64_t>(in, o::raw_checksum);
  return e;
}

std::uint64_t xxh3(std::span<const std::byte> bytes) { return XXH3_64bits(bytes.data(), bytes.size()); }

std::uint64_t header_checksum(std::span<const std::byte, kHeaderSize> header, std::span<const std::byte> table) {
  XXH3_state_t state;
  XXH3_64bits_reset(&state);
  XXH3_64bits_update(&state, header.data(), header_offset::checksum);
  XXH3_64bits_update(&state, table.data(), table.size());
  return XXH3_64bits_digest(&state);
}

void seal_header(std::span<std::byte> package) {
  if (package.size() < kHeaderSize) throw std::out_of_range("seal_header: no header");
  auto header = package.first<kHeaderSize>();
  Header h = decode_header(header);
  const auto table_size = checked_mul(std::uint64_t{h.section_count}, kEntrySize);
  const auto table_end = table_size ? checked_add(h.table_offset, *table_size) : std::nullopt;
  if (!table_end || *table_end > package.size()) throw std::out_of_range("seal_header: table outside the package");
  h.checksum = header_checksum(header, package.subspan(h.table_offset, *table_size));
  encode_header(h, header);
}

}  // namespace nano::format
