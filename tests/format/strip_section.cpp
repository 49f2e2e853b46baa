// Writes a copy of a package without one section (the rest written again, zstd where smaller, so a
// Draco-coded mesh comes out as plain sections): a package as an older baker would have written it,
// for the tests of what a reader derives when a section is absent.
//   strip_section IN.nup OUT.nup SECTION_NAME
#include <cstdio>
#include <exception>
#include <vector>

#include "format/package.hpp"
#include "format/section_kind.hpp"
#include "format/writer.hpp"

using namespace nano::format;

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: strip_section IN.nup OUT.nup SECTION_NAME\n");
    return 2;
  }
  try {
    const Package p = Package::open(argv[1]);
    const auto named = section_kind_from_name(argv[3]);
    if (!named) {
      std::fprintf(stderr, "strip_section: no section is named %s\n", argv[3]);
      return 2;
    }
    const SectionKind stripped = *named;
    if (!p.has(stripped)) {
      std::fprintf(stderr, "strip_section: %s has no section %s\n", argv[1], argv[3]);
      return 1;
    }
    std::vector<SectionSource> sections;
    for (const SectionKind kind : kAllSectionKinds) {
      if (kind == stripped || kind == SectionKind::draco_meshes || !p.has(kind)) continue;
      sections.push_back({static_cast<std::uint32_t>(kind), p.raw_bytes(kind), Compression::zstd_if_smaller, section_flags(kind)});
    }
    write_package(argv[2], sections);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strip_section: %s\n", e.what());
    return 1;
  }
  return 0;
}
