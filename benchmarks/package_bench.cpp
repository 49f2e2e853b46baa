// Package open and validation (format/): what `nanoview validate` and every renderer start pay
// before the first frame. Package::open / from_bytes do the structural checks (header, table,
// bounds, checksums, record sizes) and decompress zstd sections; validate_semantics then checks
// every index, float and AABB.
//   BM_OpenValidateMemory  from_bytes + validate_semantics of tests/format's sample scene padded to
//                          N atoms; args: atoms, zstd (0 = raw sections, 1 = zstd where smaller)
//   BM_OpenValidateMapped  open_validated of the same scene written raw to a temporary file: the
//                          mapped path (page cache warm after the first iteration)
//   BM_BundledOpen / BM_BundledValidate  Package::open, then validate_semantics alone, of a real
//                          baked package given by NANO_BENCH_PACKAGE (skipped when unset), e.g.
//                          NANO_BENCH_PACKAGE=out/virion.nup build/benchmarks/package_bench
//   BM_OpenMeshSections    from_bytes of a package holding only a UV-sphere mesh (`triangles`) whose
//                          four mesh sections are zstd (draco 0) or Draco streams (draco 1): what
//                          decoding Draco at open costs against zstd
// bytes/s counts the sections' decompressed (raw) bytes — the data actually checked — so raw and
// zstd packages compare; file_bytes is the package's size on disk. The padded sample scene repeats
// one atom, so it compresses far better than a real package: its zstd rows time the decompression
// of highly redundant data.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include <unistd.h>  // getpid

#include "benchmarks/bench_inputs.hpp"
#include "format/validator.hpp"
#include "tests/format/sample_scene.hpp"

namespace nano::bench {
namespace {

using format::test::SampleScene;

// The sample scene with `atoms` atoms (the second molecule grown), so cost per byte shows.
SampleScene scaled_sample(std::size_t atoms) {
  SampleScene s = format::test::make_sample_scene();
  s.atoms.resize(atoms, s.atoms.back());
  s.atom_info.resize(atoms, s.atom_info.back());
  s.molecules[1].atom_count = static_cast<std::uint32_t>(atoms - 3);
  s.beads.back().atom_count = static_cast<std::uint32_t>(atoms - 4);  // the copies of atom 4 join its bead
  return s;
}

// Sets bytes/s to the raw section bytes of `p` per iteration, and the file size as a counter.
void count_bytes(benchmark::State& state, const format::Package& p) {
  std::uint64_t raw = 0;
  for (const format::SectionEntry& e : p.entries()) raw += e.raw_size;
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * raw));
  state.counters["file_bytes"] = static_cast<double>(p.file_size());
}

void BM_OpenValidateMemory(benchmark::State& state) {
  const SampleScene s = scaled_sample(static_cast<std::size_t>(state.range(0)));
  const auto bytes =
      format::test::build(s, state.range(1) ? format::Compression::zstd_if_smaller : format::Compression::none);
  for (auto _ : state) {
    const format::Package p = format::Package::from_bytes(bytes);
    format::validate_semantics(p);
    benchmark::DoNotOptimize(p.file_bytes().data());
    benchmark::ClobberMemory();
  }
  count_bytes(state, format::Package::from_bytes(bytes));
}
BENCHMARK(BM_OpenValidateMemory)->ArgNames({"atoms", "zstd"})
    ->ArgsProduct({{1000, 1000000}, {0, 1}})->Unit(benchmark::kMillisecond);

void BM_OpenValidateMapped(benchmark::State& state) {
  const SampleScene s = scaled_sample(static_cast<std::size_t>(state.range(0)));
  // Per process, so concurrent runs (ctest -j) never share the file.
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("nano_package_bench_" + std::to_string(::getpid()) + ".nup");
  format::write_package(path, format::test::sections_of(s, format::Compression::none));
  for (auto _ : state) {
    const format::Package p = format::open_validated(path);
    benchmark::DoNotOptimize(p.file_bytes().data());
    benchmark::ClobberMemory();
  }
  count_bytes(state, format::Package::open(path));
  std::filesystem::remove(path);
}
BENCHMARK(BM_OpenValidateMapped)->ArgName("atoms")->Arg(1000000)->Unit(benchmark::kMillisecond);

void BM_OpenMeshSections(benchmark::State& state) {
  // rings x 2·rings quads, two triangles each (one at the poles).
  const int rings = static_cast<int>(std::sqrt(double(state.range(0)) / 4.0));
  const format::MeshArrays mesh = format::test::grid_sphere(rings, 2 * rings, 40000.f);
  gpu::Mesh record{};
  record.vertex_count = static_cast<std::uint32_t>(mesh.positions.size());
  record.triangle_count = static_cast<std::uint32_t>(mesh.triangles.size());
  const format::Compression c = state.range(1) ? format::Compression::draco : format::Compression::zstd_if_smaller;
  using format::SectionKind;
  const std::vector<format::SectionSource> sections = {
      format::section_source(SectionKind::meshes, std::span<const gpu::Mesh>(&record, 1)),
      format::section_source(SectionKind::vertex_positions, std::span(mesh.positions), c),
      format::section_source(SectionKind::vertex_normals, std::span(mesh.normals), c),
      format::section_source(SectionKind::vertex_uvs, std::span(mesh.uvs), c),
      format::section_source(SectionKind::triangles, std::span(mesh.triangles), c)};
  const auto bytes = format::build_package(sections);
  for (auto _ : state) {
    const format::Package p = format::Package::from_bytes(bytes);
    benchmark::DoNotOptimize(p.raw_bytes(SectionKind::triangles).data());
    benchmark::ClobberMemory();
  }
  count_bytes(state, format::Package::from_bytes(bytes));
  state.counters["triangles"] = static_cast<double>(mesh.triangles.size());
}
BENCHMARK(BM_OpenMeshSections)->ArgNames({"triangles", "draco"})
    ->ArgsProduct({{20000, 200000}, {0, 1}})->Unit(benchmark::kMillisecond);

std::optional<std::filesystem::path> bundled_package(benchmark::State& state) {
  const char* env = std::getenv("NANO_BENCH_PACKAGE");
  if (!env || !*env) {
    skip(state, "NANO_BENCH_PACKAGE not set");
    return std::nullopt;
  }
  if (!std::filesystem::exists(env)) {
    // Asked for but missing: a real error, not a skip.
    state.SkipWithError((std::string("NANO_BENCH_PACKAGE: no such file ") + env).c_str());
    return std::nullopt;
  }
  return std::filesystem::path(env);
}

void BM_BundledOpen(benchmark::State& state) {
  const auto path = bundled_package(state);
  if (!path) return;
  for (auto _ : state) {
    const format::Package p = format::Package::open(*path);
    benchmark::DoNotOptimize(p.file_bytes().data());
    benchmark::ClobberMemory();
  }
  count_bytes(state, format::Package::open(*path));
  state.SetLabel(path->filename().string());
}
BENCHMARK(BM_BundledOpen)->Unit(benchmark::kMillisecond);

void BM_BundledValidate(benchmark::State& state) {
  const auto path = bundled_package(state);
  if (!path) return;
  const format::Package p = format::Package::open(*path);
  for (auto _ : state) {
    format::validate_semantics(p);
    benchmark::ClobberMemory();  // validate_semantics returns nothing; it throws on a bad package
  }
  count_bytes(state, p);
  state.SetLabel(path->filename().string());
}
BENCHMARK(BM_BundledValidate)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace nano::bench

BENCHMARK_MAIN();
