#include "format/writer.hpp"

#include <algorithm>
#include <cstring>
#include <set>
#include <stdexcept>
#include <zstd.h>

#include "common/atomic_file.hpp"
#include "format/draco_mesh_sections.hpp"

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

// A section whose raw bytes are decoded from "draco_meshes": no stored bytes of its own.
Encoded draco_coded(const SectionSource& s) {
  Encoded e;
  e.entry.kind = s.kind;
  e.entry.flags = s.flags;
  e.entry.codec = static_cast<std::uint16_t>(Codec::draco);
  e.entry.raw_size = s.bytes.size();
  e.entry.stored_size = 0;
  e.entry.stored_checksum = xxh3({});
  e.entry.raw_checksum = xxh3(s.bytes);
  return e;
}

bool asks_for_draco(const SectionSource& s) {
  return s.compression == Compression::draco_if_smaller || s.compression == Compression::draco;
}

template <class T> std::span<const T> records_of(const SectionSource& s) {
  return {reinterpret_cast<const T*>(s.bytes.data()), s.bytes.size() / sizeof(T)};
}

// The mesh sections as one Draco section, or nothing when they stay zstd (see Compression).
std::vector<std::byte> draco_section_for(std::span<const SectionSource> sections, int zstd_level) {
  std::vector<const SectionSource*> group;
  const SectionSource* meshes = nullptr;
  for (const SectionSource& s : sections) {
    if (asks_for_draco(s)) group.push_back(&s);
    if (s.kind == static_cast<std::uint32_t>(SectionKind::meshes)) meshes = &s;
  }
  if (group.empty()) return {};
  const auto find = [&](SectionKind kind) -> const SectionSource& {
    for (const SectionSource* s : group)
      if (s->kind == static_cast<std::uint32_t>(kind)) return *s;
    throw std::invalid_argument("build_package: Draco asked for some mesh sections but not " + section_kind_name(kind));
  };
  for (const SectionSource* s : group)
    if (!is_draco_coded_kind(s->kind) || s->compression != group.front()->compression)
      throw std::invalid_argument("build_package: Draco asked for " + section_kind_name(s->kind) +
                                  "; only the four mesh sections may, all alike");
  if (!meshes) throw std::invalid_argument("build_package: Draco mesh sections need section meshes");
  const bool demanded = group.front()->compression == Compression::draco;
  const DracoEncoding encoding = encode_draco_meshes(
      records_of<gpu::Mesh>(*meshes), records_of<glm::vec4>(find(SectionKind::vertex_positions)),
      records_of<glm::vec4>(find(SectionKind::vertex_normals)), records_of<glm::vec2>(find(SectionKind::vertex_uvs)),
      records_of<gpu::Triangle>(find(SectionKind::triangles)), kDefaultDracoSpeed);
  if (!encoding.why.empty()) {
    if (demanded) throw std::runtime_error("the meshes cannot be stored as Draco: " + encoding.why);
    return {};
  }
  if (!demanded) {
    std::uint64_t zstd = 0;
    for (const SectionSource* s : group) zstd += zstd_stored_size(s->bytes, zstd_level);
    if (encoding.section.size() >= zstd) return {};
  }
  return encoding.section;
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

std::uint64_t zstd_stored_size(std::span<const std::byte> raw, int zstd_level) {
  const std::vector<std::byte> compressed = compress_if_smaller(raw, zstd_level);
  return compressed.empty() ? raw.size() : compressed.size();
}

std::vector<std::byte> build_package(std::span<const SectionSource> given, int zstd_level) {
  check_sources(given);
  const std::vector<std::byte> draco = draco_section_for(given, zstd_level);
  // The Draco section goes where the mesh sections' bytes would have been: after "triangles".
  std::vector<SectionSource> sections;
  for (const SectionSource& s : given) {
    sections.push_back(s);
    if (!draco.empty() && s.kind == static_cast<std::uint32_t>(SectionKind::triangles))
      sections.push_back(section_source(SectionKind::draco_meshes, std::span<const std::byte>(draco),
                                        default_compression(SectionKind::draco_meshes)));
  }
  check_sources(sections);
  std::vector<Encoded> encoded;
  encoded.reserve(sections.size());
  for (SectionSource s : sections) {
    if (asks_for_draco(s) && !draco.empty()) {
      encoded.push_back(draco_coded(s));
      continue;
    }
    if (asks_for_draco(s)) s.compression = Compression::zstd_if_smaller;
    encoded.push_back(encode(s, zstd_level));
  }

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
    if (e.entry.codec == static_cast<std::uint16_t>(Codec::draco)) continue;  // its bytes are in draco_meshes
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
