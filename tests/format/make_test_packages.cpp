// Writes the packages the CLI tests run `nanoview validate` on (and the fuzz seeds):
// valid.nup, valid-raw.nup, bad-checksum.nup, bad-atom-range.nup, empty.nup.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/atomic_file.hpp"
#include "tests/format/package_bytes.hpp"
#include "tests/format/sample_scene.hpp"

using namespace nano::format;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_test_packages OUTPUT_DIR\n");
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  test::SampleScene s = test::make_sample_scene();
  write_package(dir / "valid.nup", test::sections_of(s, Compression::zstd_if_smaller));
  write_package(dir / "valid-raw.nup", test::sections_of(s, Compression::none));

  std::vector<std::byte> flipped = test::build(s, Compression::none);
  const std::size_t atoms = test::entry_at(test::entry_index(flipped, SectionKind::atoms));
  flipped[test::get_le(flipped, atoms + 8, 8) + 5] ^= std::byte{0x20};
  nano::write_file_atomically(dir / "bad-checksum.nup", flipped);

  s.molecules[1].atom_count = 7;
  write_package(dir / "bad-atom-range.nup", test::sections_of(s, Compression::none));
  nano::write_file_atomically(dir / "empty.nup", std::span<const std::byte>{});
  return 0;
}
