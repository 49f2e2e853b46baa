#pragma once
// A .nup package opened for reading: the file is memory-mapped read-only and its structure is
// validated (header, table, bounds, alignment, overlaps, padding, checksums, record sizes,
// decompression) before any section is handed out. Sections stored raw are used in place from the
// map; zstd sections are decompressed once, at open. Semantic checks (indices, floats, AABBs) are
// in format/validator.hpp.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "format/layout.hpp"
#include "format/package_error.hpp"
#include "format/section_kind.hpp"

namespace nano::format {

class Package {
public:
  // Throws PackageError (a nano::InputError) naming the file for anything wrong with it.
  static Package open(const std::filesystem::path& path);
  // Same checks on bytes in memory; they are copied to storage aligned like a mapped file.
  static Package from_bytes(std::span<const std::byte> bytes, std::string name = "<memory>");

  Package(Package&&) noexcept;
  Package& operator=(Package&&) noexcept;
  ~Package();

  const std::string& name() const;
  const Header& header() const;
  std::uint64_t file_size() const;
  // The whole file as it is held: the read-only mapping (memory_mapped(): page-aligned, so a device
  // may import its pages, VK_EXT_external_memory_host) or an aligned heap copy (from_bytes).
  std::span<const std::byte> file_bytes() const;
  bool memory_mapped() const;
  // The table in file order, including sections of kinds this reader does not know.
  std::span<const SectionEntry> entries() const;

  bool has(SectionKind kind) const;
  const SectionEntry* entry(SectionKind kind) const;  // nullptr if absent
  // The raw (decompressed) bytes of a section; empty if the section is absent.
  std::span<const std::byte> raw_bytes(SectionKind kind) const;
  std::uint64_t record_count(SectionKind kind) const;
  // Where a byte of a section's raw data is, for error reports.
  Location locate(SectionKind kind, std::uint64_t raw_offset) const;

  template <SectionKind K> std::span<const record_t<K>> records() const {
    const std::span<const std::byte> bytes = raw_bytes(K);
    // Sizes are whole records (checked at open) and data starts 256-aligned in the map or at
    // operator new's alignment, which exceeds every record's alignment.
    return {reinterpret_cast<const record_t<K>*>(bytes.data()), bytes.size() / sizeof(record_t<K>)};
  }

  struct Impl;  // opaque: the storage and decoded table, defined in package.cpp

private:
  explicit Package(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace nano::format
