#include "format/writer.hpp"

#include <algorithm>
#include <cstring>
#include <set>
#include <stdexcept>
#include <zstd.h>

#include "common/atomic_file.hpp"

namespace nano::format {
namespace {

struct Encoded {
  SectionEntry entry;
  std::vector<std::byte> compressed;  // empty when stored raw
};

// zstd frame with the content size recorded (the reader insists on it), or nothing if it does not
// make the section smaller.
std::vector<std::byte> compress_if_smaller(std::span<const std::byte> raw, int level) {
  if (raw.empty()) return {};
  std::vector<std::byte> out(ZSTD_compressBound(raw.size()));
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
  if (!cctx) throw std::bad_alloc();
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_compressionLevel, level);
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_contentSizeFlag, 1);
  ZSTD_CCtx_setParameter(cctx, ZSTD_c_checksumFlag, 0);  // our XXH3 of the raw bytes covers it
  const std::size_t n = ZSTD_compress2(cctx, out.data(), out.size(), raw.data(), raw.size());
  ZSTD_freeCCtx(cctx);
  if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));
  if (n >= raw.size()) return {};
  out.resize(n);
  return out;
}

Encoded encode(const SectionSource& s, int level) {
  Encoded e;
  e.entry.kind = s.kind;
  e.entry.flags = s.flags;
  e.entry.raw_size = s.bytes.size();
  if (s.compression == Compression::zstd_if_smaller) e.compressed = compress_if_smaller(s.bytes, level);
  if (e.compressed.empty()) {
    e.entry.codec = static_cast<std::uint16_t>(Codec::none);
    e.entry.stored_size = s.bytes.size();
    e.entry.stored_checksum = xxh3(s.bytes);
  } else {
    e.entry.codec = static_cast<std::uint16_t>(Codec::zstd);
    e.entry.stored_size = e.compressed.size();
    e.entry.stored_checksum = xxh3(e.compressed);
    e.entry.raw_checksum = xxh3(s.bytes);
  }
  return e;
}

void check_sources(std::span<const SectionSource> sections) {
  if (sections.size() > kMaxSections) throw std::invalid_argument("build_package: too many sections");
  std::set<std::uint32_t> kinds;
  for (const SectionSource& s : sections) {
    if (!kinds.insert(s.kind).second)
      throw std::invalid_argument("build_package: section " + section_kind_name(s.kind) + " given twice");
    if (is_known_section_kind(s.kind) && s.bytes.size() % record_size(static_cast<SectionKind>(s.kind)) != 0)
      throw std::invalid_argument("build_package: section " + section_kind_name(s.kind) +
                                  " is not a whole number of records");
  }
}

}  // namespace

std::vector<std::byte> build_package(std::span<const SectionSource> sections, int zstd_level) {
  check_sources(sections);
  std::vector<Encoded> encoded;
  encoded.reserve(sections.size());
  for (const SectionSource& s : sections) encoded.push_back(encode(s, zstd_level));

  std::uint64_t cursor = kHeaderSize + kEntrySize * sections.size();
  for (Encoded& e : encoded) {
    e.entry.offset = align_up(cursor, kSectionAlignment);
    cursor = e.entry.offset + e.entry.stored_size;
  }
  // Zero-initialised: every gap is the zero padding the reader requires.
  std::vector<std::byte> file(cursor);
  Header header;
  header.file_size = file.size();
  header.section_count = static_cast<std::uint32_t>(sections.size());
  encode_header(header, std::span(file).first<kHeaderSize>());
  for (std::size_t i = 0; i < encoded.size(); ++i) {
    const Encoded& e = encoded[i];
    encode_section_entry(e.entry, std::span(file).subspan(kHeaderSize + i * kEntrySize).first<kEntrySize>());
    const std::span<const std::byte> stored = e.compressed.empty() ? sections[i].bytes : std::span<const std::byte>(e.compressed);
    if (!stored.empty()) std::memcpy(file.data() + e.entry.offset, stored.data(), stored.size());
  }
  seal_header(file);
  return file;
}

void write_package(const std::filesystem::path& path, std::span<const SectionSource> sections, int zstd_level) {
  const std::vector<std::byte> bytes = build_package(sections, zstd_level);
  write_file_atomically(path, bytes);
}

}  // namespace nano::format
