#include "format/package.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <deque>
#include <fcntl.h>
#include <new>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "format/checked_math.hpp"
#include "format/draco_mesh_sections.hpp"
#include "format/zstd_bounded.hpp"

namespace nano::format {
namespace {

// The fuzz build (NANO_FUZZ_ONLY) still computes every checksum but ignores mismatches, so that
// mutated inputs reach the decoding and semantic checks behind them instead of all dying at the
// first checksum. The convention libFuzzer/OSS-Fuzz use for exactly this.
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
constexpr bool kEnforceChecksums = false;
#else
constexpr bool kEnforceChecksums = true;
#endif

bool mismatch(std::uint64_t computed, std::uint64_t stored) { return computed != stored && kEnforceChecksums; }

// Keeps the file bytes alive: either a read-only mapping or an aligned heap copy.
class Storage {
public:
  static Storage map(const std::filesystem::path& path) {
    Storage s;
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw InputError(path.string(), "", std::string("cannot open: ") + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
      ::close(fd);
      throw InputError(path.string(), "", "not a regular file");
    }
    s.size_ = static_cast<std::uint64_t>(st.st_size);
    if (s.size_ > 0) {
      void* p = ::mmap(nullptr, s.size_, PROT_READ, MAP_PRIVATE, fd, 0);
      if (p == MAP_FAILED) {
        const int err = errno;
        ::close(fd);
        throw InputError(path.string(), "", std::string("cannot map: ") + std::strerror(err));
      }
      s.data_ = static_cast<const std::byte*>(p);
      s.mapped_ = true;
    }
    ::close(fd);
    return s;
  }

  static Storage copy(std::span<const std::byte> bytes) {
    Storage s;
    s.size_ = bytes.size();
    if (!bytes.empty()) {
      auto* p = static_cast<std::byte*>(::operator new(bytes.size(), std::align_val_t{kSectionAlignment}));
      std::memcpy(p, bytes.data(), bytes.size());
      s.data_ = p;
    }
    return s;
  }

  Storage() = default;
  Storage(Storage&& o) noexcept { *this = std::move(o); }
  Storage& operator=(Storage&& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    std::swap(mapped_, o.mapped_);
    return *this;
  }
  ~Storage() {
    if (!data_) return;
    if (mapped_) ::munmap(const_cast<std::byte*>(data_), size_);
    else ::operator delete(const_cast<std::byte*>(data_), std::align_val_t{kSectionAlignment});
  }
  std::span<const std::byte> bytes() const { return {data_, size_}; }
  bool mapped() const { return mapped_; }

private:
  const std::byte* data_ = nullptr;
  std::uint64_t size_ = 0;
  bool mapped_ = false;
};

}  // namespace

struct Package::Impl {
  std::string name;
  Storage storage;
  Header header;
  std::vector<SectionEntry> entries;
  // Raw bytes of each known kind present, indexed by kind value.
  std::array<std::span<const std::byte>, std::size(kAllSectionKinds) + 1> raw{};
  std::array<const SectionEntry*, std::size(kAllSectionKinds) + 1> entry_of{};
  std::deque<std::vector<std::byte>> inflated;  // a deque: spans into earlier ones stay valid
};

namespace {

// Structural validation of the whole file, in the order that gives the most useful message:
// identity (magic, endianness, version) first, so a file from another major version is named as
// such rather than as a checksum failure; then the header's own fields; then each section.
class StructureCheck {
public:
  StructureCheck(Package::Impl& p) : p_(p), file_(p.storage.bytes()) {}

  void run() {
    check_identity();
    check_header_fields();
    read_table();
    check_regions();
    for (const SectionEntry& e : p_.entries) check_section(e);
    decode_draco_sections();
  }

private:
  [[noreturn]] void fail(Rule rule, Location where, const std::string& detail) const {
    throw PackageError(p_.name, rule, where, detail);
  }
  static Location at(std::uint64_t offset) { return {std::nullopt, offset, false}; }
  static Location in(const SectionEntry& e, std::uint64_t offset) { return {e.kind, offset, false}; }

  void check_identity() {
    if (file_.size() < kHeaderSize)
      fail(Rule::truncated, at(file_.size()),
           file_.empty() ? "empty file, not a package"
                         : "file is " + std::to_string(file_.size()) + " bytes, shorter than the 64-byte header");
    if (std::memcmp(file_.data(), kMagic.data(), kMagic.size()) != 0)
      fail(Rule::bad_magic, at(0), "not a .nup package (magic bytes differ)");
    p_.header = decode_header(file_.first<kHeaderSize>());
    const Header& h = p_.header;
    if (h.endian_mark != kEndianMark)
      fail(Rule::bad_endianness, at(header_offset::endian_mark),
           h.endian_mark == __builtin_bswap32(kEndianMark) ? "package was written big-endian; only little-endian is supported"
                                                            : "endianness mark is not 04 03 02 01");
    if (h.version_major != kVersionMajor)
      fail(Rule::unsupported_version, at(header_offset::version_major),
           "format version " + std::to_string(h.version_major) + "." + std::to_string(h.version_minor) +
               " found; this reader supports major version " + std::to_string(kVersionMajor) + " (up to " +
               std::to_string(kVersionMajor) + "." + std::to_string(kVersionMinor) + ")");
  }

  void check_header_fields() {
    const Header& h = p_.header;
    if (h.file_size != file_.size())
      fail(Rule::file_size_mismatch, at(header_offset::file_size),
           "header says " + std::to_string(h.file_size) + " bytes, file has " + std::to_string(file_.size()));
    if (h.section_count > kMaxSections)
      fail(Rule::table_bounds, at(header_offset::section_count),
           std::to_string(h.section_count) + " sections exceed the maximum of " + std::to_string(kMaxSections));
    const std::uint64_t table_size = std::uint64_t{h.section_count} * kEntrySize;  // cannot overflow: count capped
    if (h.table_offset < kHeaderSize || !range_within(h.table_offset, table_size, file_.size()))
      fail(Rule::table_bounds, at(header_offset::table_offset),
           "section table at " + std::to_string(h.table_offset) + " (" + std::to_string(table_size) +
               " bytes) is not between the header and the end of the file");
    table_end_ = h.table_offset + table_size;
    const std::uint64_t sum = header_checksum(file_.first<kHeaderSize>(), file_.subspan(h.table_offset, table_size));
    if (mismatch(sum, h.checksum)) fail(Rule::header_checksum, at(header_offset::checksum), "header and table checksum mismatch");
    if (h.flags != 0) fail(Rule::nonzero_reserved, at(header_offset::flags), "header flags must be zero");
    if (h.reserved0 != 0) fail(Rule::nonzero_reserved, at(header_offset::reserved0), "reserved header field must be zero");
    if (h.reserved1 != 0) fail(Rule::nonzero_reserved, at(header_offset::reserved1), "reserved header field must be zero");
  }

  void read_table() {
    const Header& h = p_.header;
    p_.entries.reserve(h.section_count);
    std::array<bool, std::size(kAllSectionKinds) + 1> seen{};
    for (std::uint32_t i = 0; i < h.section_count; ++i) {
      const std::uint64_t at_entry = h.table_offset + i * kEntrySize;
      const SectionEntry e = decode_section_entry(file_.subspan(at_entry).first<kEntrySize>());
      if (e.codec > static_cast<std::uint16_t>(Codec::draco))
        fail(Rule::unknown_codec, in(e, at_entry + entry_offset::codec), "codec " + std::to_string(e.codec) + " is unknown");
      if (e.flags & ~kKnownSectionFlags)
        fail(Rule::nonzero_reserved, in(e, at_entry + entry_offset::flags), "unknown section flag bits");
      if (e.offset % kSectionAlignment != 0)
        fail(Rule::misaligned, in(e, at_entry + entry_offset::offset),
             "offset " + std::to_string(e.offset) + " is not a multiple of 256");
      if (e.offset < table_end_ || !range_within(e.offset, e.stored_size, file_.size()))
        fail(Rule::section_bounds, in(e, at_entry + entry_offset::offset),
             "stored bytes [" + std::to_string(e.offset) + ", +" + std::to_string(e.stored_size) +
                 ") are not between the table end (" + std::to_string(table_end_) + ") and the file end (" +
                 std::to_string(file_.size()) + ")");
      if (is_known_section_kind(e.kind)) {
        if (seen[e.kind]) fail(Rule::duplicate_section, in(e, at_entry), "section kind appears twice");
        seen[e.kind] = true;
      }
      p_.entries.push_back(e);
    }
    // Pointers taken only now that the vector is complete.
    for (const SectionEntry& e : p_.entries)
      if (is_known_section_kind(e.kind)) p_.entry_of[e.kind] = &e;
  }

  // Header, table and sections must not overlap, and every other byte must be zero, so that any
  // changed byte anywhere in the file breaks either a checksum or this rule.
  void check_regions() {
    struct Region { std::uint64_t begin, end; const SectionEntry* entry; };
    std::vector<Region> regions{{0, table_end_, nullptr}};
    for (const SectionEntry& e : p_.entries)
      if (e.stored_size > 0) regions.push_back({e.offset, e.offset + e.stored_size, &e});
    std::sort(regions.begin(), regions.end(), [](const Region& a, const Region& b) { return a.begin < b.begin; });
    std::uint64_t cursor = 0;
    const SectionEntry* previous = nullptr;
    for (const Region& r : regions) {
      if (r.begin < cursor)
        fail(Rule::overlap, in(*r.entry, r.begin),
             "overlaps " + (previous ? "section " + section_kind_name(previous->kind) : std::string("the header/table")));
      check_zero(cursor, r.begin);
      cursor = r.end;
      previous = r.entry;
    }
    check_zero(cursor, file_.size());
  }

  void check_zero(std::uint64_t begin, std::uint64_t end) const {
    for (std::uint64_t i = begin; i < end; ++i)
      if (file_[i] != std::byte{0}) fail(Rule::nonzero_padding, at(i), "padding byte is not zero");
  }

  void check_section(const SectionEntry& e) {
    const std::span<const std::byte> stored = file_.subspan(e.offset, e.stored_size);
    if (mismatch(xxh3(stored), e.stored_checksum)) fail(Rule::stored_checksum, in(e, e.offset), "checksum of stored bytes mismatch");
    // Unknown optional kinds are verified as far as the checksum and then skipped.
    if (!is_known_section_kind(e.kind)) {
      if (e.flags & kSectionRequired)
        fail(Rule::unknown_required_section, in(e, e.offset),
             "section kind is unknown to this reader (format " + std::to_string(kVersionMajor) + "." +
                 std::to_string(kVersionMinor) + ") and marked required");
      return;
    }
    const std::uint64_t rec = record_size(static_cast<SectionKind>(e.kind));
    if (e.raw_size % rec != 0)
      fail(Rule::record_size, in(e, e.offset),
           "raw size " + std::to_string(e.raw_size) + " is not a multiple of the record size " + std::to_string(rec));
    if (e.codec == static_cast<std::uint16_t>(Codec::none)) {
      if (e.raw_size != e.stored_size)
        fail(Rule::record_size, in(e, e.offset), "uncompressed section with raw size different from stored size");
      if (e.raw_checksum != 0) fail(Rule::nonzero_reserved, in(e, e.offset), "raw checksum of an uncompressed section must be zero");
      p_.raw[e.kind] = stored;
      return;
    }
    if (e.codec == static_cast<std::uint16_t>(Codec::draco)) {
      if (!is_draco_coded_kind(e.kind))
        fail(Rule::mesh_codec, in(e, e.offset), "codec draco serves only " + draco_coded_kind_names());
      if (e.stored_size != 0) fail(Rule::mesh_codec, in(e, e.offset), "a Draco-coded section stores no bytes of its own");
      if (e.raw_size > kMaxRawSectionBytes)
        fail(Rule::raw_size_limit, in(e, e.offset), "claimed raw size " + std::to_string(e.raw_size) + " exceeds the cap (64 GiB)");
      return;  // decoded with the others by decode_draco_sections
    }
    if (e.raw_size > kMaxRawSectionBytes || e.raw_size / kMaxZstdExpansion > e.stored_size)
      fail(Rule::raw_size_limit, in(e, e.offset),
           "claimed raw size " + std::to_string(e.raw_size) + " exceeds the cap (64 GiB, and 32768x the stored size)");
    std::vector<std::byte> raw;
    try {
      raw = inflate_bounded(stored, e.raw_size);
    } catch (const ZstdFrameError& z) {
      fail(Rule::decompression, in(e, e.offset), z.what());
    }
    if (mismatch(xxh3(raw), e.raw_checksum)) fail(Rule::raw_checksum, in(e, e.offset), "checksum of decompressed bytes mismatch");
    p_.inflated.push_back(std::move(raw));
    p_.raw[e.kind] = p_.inflated.back();
  }

  // The four mesh sections are Draco-coded together or not at all, and "draco_meshes" exists exactly
  // when they are. Their raw bytes are then decoded from it, sized against each entry and checked
  // against its raw checksum like a zstd section's.
  void decode_draco_sections() {
    const SectionEntry* streams = p_.entry_of[static_cast<std::uint32_t>(SectionKind::draco_meshes)];
    int coded = 0;
    const SectionEntry* some_coded = nullptr;
    for (const SectionKind k : kDracoCodedKinds) {
      const SectionEntry* e = p_.entry_of[static_cast<std::uint32_t>(k)];
      if (e && e->codec == static_cast<std::uint16_t>(Codec::draco)) ++coded, some_coded = e;
    }
    if (coded == 0 && !streams) return;
    if (!streams)
      fail(Rule::missing_section, in(*some_coded, some_coded->offset), "a mesh section is Draco-coded but section draco_meshes is absent");
    if (coded != int(std::size(kDracoCodedKinds)))
      fail(Rule::mesh_codec, in(*streams, streams->offset),
           "section draco_meshes needs all four of " + draco_coded_kind_names() + " Draco-coded; " +
               std::to_string(coded) + " are");
    const SectionEntry* meshes = p_.entry_of[static_cast<std::uint32_t>(SectionKind::meshes)];
    if (!meshes) fail(Rule::missing_section, in(*streams, streams->offset), "Draco-coded mesh sections need section meshes");
    const std::span<const std::byte> mesh_bytes = p_.raw[static_cast<std::uint32_t>(SectionKind::meshes)];
    const std::span<const gpu::Mesh> records(reinterpret_cast<const gpu::Mesh*>(mesh_bytes.data()), mesh_bytes.size() / sizeof(gpu::Mesh));
    const auto raw_records = [&](SectionKind k) { return p_.entry_of[static_cast<std::uint32_t>(k)]->raw_size / record_size(k); };
    MeshArrays decoded;
    try {
      decoded = decode_draco_meshes(p_.raw[static_cast<std::uint32_t>(SectionKind::draco_meshes)], records,
                                    raw_records(SectionKind::vertex_positions), raw_records(SectionKind::triangles));
    } catch (const DracoSectionError& d) {
      // As everywhere: a file offset for a section stored raw, else an offset in its decompressed bytes.
      const bool raw = streams->codec == static_cast<std::uint16_t>(Codec::none);
      fail(Rule::decompression, {streams->kind, raw ? streams->offset + d.offset() : d.offset(), !raw}, d.what());
    }
    keep_decoded(SectionKind::vertex_positions, std::as_bytes(std::span(decoded.positions)));
    keep_decoded(SectionKind::vertex_normals, std::as_bytes(std::span(decoded.normals)));
    keep_decoded(SectionKind::vertex_uvs, std::as_bytes(std::span(decoded.uvs)));
    keep_decoded(SectionKind::triangles, std::as_bytes(std::span(decoded.triangles)));
  }

  void keep_decoded(SectionKind kind, std::span<const std::byte> bytes) {
    const SectionEntry& e = *p_.entry_of[static_cast<std::uint32_t>(kind)];
    if (bytes.size() != e.raw_size)
      fail(Rule::decompression, in(e, e.offset),
           "decodes to " + std::to_string(bytes.size()) + " bytes, the table says " + std::to_string(e.raw_size));
    if (mismatch(xxh3(bytes), e.raw_checksum)) fail(Rule::raw_checksum, in(e, e.offset), "checksum of decoded bytes mismatch");
    p_.inflated.emplace_back(bytes.begin(), bytes.end());
    p_.raw[e.kind] = p_.inflated.back();
  }

  Package::Impl& p_;
  std::span<const std::byte> file_;
  std::uint64_t table_end_ = 0;
};

}  // namespace

Package::Package(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Package::Package(Package&&) noexcept = default;
Package& Package::operator=(Package&&) noexcept = default;
Package::~Package() = default;

Package Package::open(const std::filesystem::path& path) {
  auto impl = std::make_unique<Impl>();
  impl->name = path.string();
  impl->storage = Storage::map(path);
  StructureCheck(*impl).run();
  return Package(std::move(impl));
}

Package Package::from_bytes(std::span<const std::byte> bytes, std::string name) {
  auto impl = std::make_unique<Impl>();
  impl->name = std::move(name);
  impl->storage = Storage::copy(bytes);
  StructureCheck(*impl).run();
  return Package(std::move(impl));
}

const std::string& Package::name() const { return impl_->name; }
const Header& Package::header() const { return impl_->header; }
std::uint64_t Package::file_size() const { return impl_->storage.bytes().size(); }
std::span<const std::byte> Package::file_bytes() const { return impl_->storage.bytes(); }
bool Package::memory_mapped() const { return impl_->storage.mapped(); }
std::span<const SectionEntry> Package::entries() const { return impl_->entries; }
bool Package::has(SectionKind kind) const { return entry(kind) != nullptr; }
const SectionEntry* Package::entry(SectionKind kind) const { return impl_->entry_of[static_cast<std::uint32_t>(kind)]; }
std::span<const std::byte> Package::raw_bytes(SectionKind kind) const { return impl_->raw[static_cast<std::uint32_t>(kind)]; }
std::uint64_t Package::record_count(SectionKind kind) const { return raw_bytes(kind).size() / record_size(kind); }

Location Package::locate(SectionKind kind, std::uint64_t raw_offset) const {
  const SectionEntry* e = entry(kind);
  if (!e) return {static_cast<std::uint32_t>(kind), 0, false};
  if (e->codec == static_cast<std::uint16_t>(Codec::none)) return {e->kind, e->offset + raw_offset, false};
  return {e->kind, raw_offset, true};
}

}  // namespace nano::format
