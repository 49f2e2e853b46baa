// libFuzzer's entry points for nano_fuzzer, the one executable of every reader target (one compile
// of each source and one link, where a target per reader recompiled the same code twelve times). The
// reader is chosen per process, by NANO_FUZZ_READER, so that each still gets a campaign, a corpus
// and a report of its own (run_fuzz.sh; docs/tests.md, "Fuzzing").
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "bake/mesh/mesh_reader.hpp"
#include "bake/structure/structure_reader.hpp"

namespace nano::fuzz {

using Bytes = std::span<const std::byte>;

// Defined beside their checks in package_fuzzer.cpp, scene_fuzzer.cpp, recipe_fuzzer.cpp,
// mesh_fuzzer.cpp and structure_fuzzer.cpp; declared here, without a header, as the table below is
// their one caller.
void fuzz_package(Bytes bytes);
void fuzz_scene(Bytes bytes);
void fuzz_recipe(Bytes bytes);
void fuzz_mesh(mesh::MeshFormat format, Bytes bytes);
void fuzz_structure(std::optional<structure::StructureFormat> format, Bytes bytes);

}  // namespace nano::fuzz

namespace {

using namespace nano::fuzz;
using nano::mesh::MeshFormat;
using nano::structure::StructureFormat;

template <MeshFormat F> void fuzz_mesh_format(Bytes bytes) { fuzz_mesh(F, bytes); }
template <StructureFormat F> void fuzz_structure_format(Bytes bytes) { fuzz_structure(F, bytes); }
void fuzz_structure_bytes(Bytes bytes) { fuzz_structure(std::nullopt, bytes); }

struct Reader {
  std::string_view name;  // run_fuzz.sh's session name
  void (*fuzz)(Bytes bytes);
};

constexpr Reader kReaders[] = {
    {"package", fuzz_package},
    {"scene", fuzz_scene},
    {"recipe", fuzz_recipe},
    {"obj", fuzz_mesh_format<MeshFormat::obj>},
    {"off", fuzz_mesh_format<MeshFormat::off>},
    {"ply", fuzz_mesh_format<MeshFormat::ply>},
    {"stl", fuzz_mesh_format<MeshFormat::stl>},
    {"draco", fuzz_mesh_format<MeshFormat::draco>},
    {"collada", fuzz_mesh_format<MeshFormat::collada>},
    {"pdb", fuzz_structure_format<StructureFormat::Pdb>},
    {"mmcif", fuzz_structure_format<StructureFormat::Mmcif>},
    {"gzip", fuzz_structure_bytes},
};

constexpr const char* kReaderVariable = "NANO_FUZZ_READER";

void (*chosen_reader)(Bytes bytes) = nullptr;

}  // namespace

// An unset or misspelt variable stops the process before any input is run: fuzzing the wrong
// reader, or none, would pass unnoticed.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const char* name = std::getenv(kReaderVariable);
  for (const Reader& reader : kReaders)
    if (name && reader.name == name) {
      chosen_reader = reader.fuzz;
      return 0;
    }
  std::string names;
  for (const Reader& reader : kReaders) names.append(" ").append(reader.name);
  if (name) std::fprintf(stderr, "nano_fuzzer: %s=%s names no reader; valid names:%s\n", kReaderVariable, name, names.c_str());
  else std::fprintf(stderr, "nano_fuzzer: %s is not set; set it to the reader to fuzz, one of:%s\n", kReaderVariable, names.c_str());
  std::exit(2);
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  chosen_reader(std::as_bytes(std::span(data, size)));
  return 0;
}
