// Open + structural + semantic validation of a package, from memory and from a mapped file.
// Not run by ctest: build-format/tests/format/format_bench
#include <benchmark/benchmark.h>

#include <filesystem>

#include "format/validator.hpp"
#include "tests/format/sample_scene.hpp"

namespace nano::format::test {
namespace {

// The sample scene with `n` atoms, so cost per byte shows.
SampleScene scaled(std::size_t atoms) {
  SampleScene s = make_sample_scene();
  s.atoms.resize(atoms, s.atoms.back());
  s.atom_info.resize(atoms, s.atom_info.back());
  s.molecules[1].atom_count = static_cast<std::uint32_t>(atoms - 3);
  return s;
}

void BM_OpenValidateMemory(benchmark::State& state) {
  const SampleScene s = scaled(state.range(0));
  const auto bytes = build(s, state.range(1) ? Compression::zstd_if_smaller : Compression::none);
  for (auto _ : state) {
    const Package p = Package::from_bytes(bytes);
    validate_semantics(p);
    benchmark::DoNotOptimize(p.file_size());
  }
  state.SetBytesProcessed(state.iterations() * bytes.size());
}
BENCHMARK(BM_OpenValidateMemory)->ArgsProduct({{1000, 1000000}, {0, 1}})->Unit(benchmark::kMillisecond);

void BM_OpenValidateMapped(benchmark::State& state) {
  const SampleScene s = scaled(state.range(0));
  const auto path = std::filesystem::temp_directory_path() / "nano_format_bench.nup";
  write_package(path, sections_of(s, Compression::none));
  for (auto _ : state) benchmark::DoNotOptimize(open_validated(path).file_size());
  state.SetBytesProcessed(state.iterations() * std::filesystem::file_size(path));
  std::filesystem::remove(path);
}
BENCHMARK(BM_OpenValidateMapped)->Arg(1000000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace nano::format::test

BENCHMARK_MAIN();
