// Writes the packages the CLI tests run `nanoview validate` on (and the fuzz seeds):
// valid.nup, valid-raw.nup, valid-draco.nup, bad-checksum.nup, bad-draco-step.nup,
// bad-atom-range.nup, empty.nup.
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
  write_package(dir / "valid-draco.nup", test::sections_of(s, Compression::draco));

  // Mesh 0's position step made 3: no power of two, so its floats would be no grid's.
  std::vector<std::byte> draco = build_package(test::sections_of(s, Compression::draco));
  const std::size_t streams = test::get_le(draco, test::entry_at(test::entry_index(draco, SectionKind::draco_meshes)) + 8, 8);
  test::put_le(draco, streams + 16, 4, 0x40400000u);  // 3.0f
  nano::write_file_atomically(dir / "bad-draco-step.nup", test::resealed(draco));

  std::vector<std::byte> flipped = test::build(s, Compression::none);
  const std::size_t atoms = test::entry_at(test::entry_index(flipped, SectionKind::atoms));
  flipped[test::get_le(flipped, atoms + 8, 8) + 5] ^= std::byte{0x20};
  nano::write_file_atomically(dir / "bad-checksum.nup", flipped);

  s.molecules[1].atom_count = 7;
  write_package(dir / "bad-atom-range.nup", test::sections_of(s, Compression::none));
  nano::write_file_atomically(dir / "empty.nup", std::span<const std::byte>{});
  return 0;
}
