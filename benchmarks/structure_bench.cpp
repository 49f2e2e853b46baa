// Structure reader throughput: the 23,694-atom spike (PDB) and the largest biopython mmCIF,
// read straight from its .gz (so the mmCIF figure includes inflating it).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "bake/structure/mmcif_parser.hpp"
#include "bake/structure/pdb_parser.hpp"
#include "bake/structure/structure_reader.hpp"
#include "bake/structure/structure_text.hpp"

namespace {

void read_file(benchmark::State& state, const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("missing input " + path.string()).c_str());
    return;
  }
  using namespace nano::structure;
  const std::string text = read_structure_text(path);
  const std::size_t text_bytes = text.size();
  // Records parsed (all models) can far exceed the atoms kept (first model) for NMR files.
  const std::size_t records = (detect_structure_format(path, text) == StructureFormat::Mmcif ? parse_mmcif(text, "")
                                                                                             : parse_pdb(text, ""))
                                  .atoms.size();
  std::size_t atoms = 0;
  for (auto _ : state) {
    const Molecule molecule = read_molecule(path, {});
    atoms = molecule.atoms.size();
    benchmark::DoNotOptimize(molecule.atoms.data());
  }
  state.counters["atoms"] = static_cast<double>(atoms);
  state.counters["atoms/s"] = benchmark::Counter(static_cast<double>(atoms), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["records/s"] = benchmark::Counter(static_cast<double>(records), benchmark::Counter::kIsIterationInvariantRate);
  // Bytes of (decompressed) text parsed per second.
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text_bytes));
}

}  // namespace

BENCHMARK_CAPTURE(read_file, spike_6vxx_pdb, std::filesystem::path(NANO_SHARED_PDB_DIR) / "6vxx.pdb")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_file, popc_patch_pdb, std::filesystem::path(NANO_SHARED_PDB_DIR) / "popc.pdb")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(read_file, biopython_2BEG_cif_gz, std::filesystem::path(NANO_BIOPYTHON_PDB_DIR) / "2BEG.cif.gz")
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
