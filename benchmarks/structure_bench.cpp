// Structure reader throughput (bake/structure): the whole read_molecule path the baker runs per
// molecule — read (and inflate .gz), detect the format, parse, select, assign radii — on the
// in-repository structures, plus the largest mmCIF of Debian's biopython test files when installed.
//   atoms/s    atoms kept after selection per second (what the baker gets)
//   records/s  atom records parsed per second (all models: an NMR file parses more than it keeps)
//   bytes/s    (decompressed) text per second: comparable across formats and file sizes
#include <filesystem>
#include <string>

#include "benchmarks/bench_inputs.hpp"
#include "bake/structure/mmcif_parser.hpp"
#include "bake/structure/pdb_parser.hpp"
#include "bake/structure/structure_reader.hpp"
#include "bake/structure/structure_text.hpp"

namespace nano::bench {
namespace {

void BM_ReadMolecule(benchmark::State& state, const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) return skip(state, "no " + path.string());
  using namespace nano::structure;
  // Untimed: the sizes the counters divide by.
  const std::string text = read_structure_text(path);
  const std::size_t records =
      (detect_structure_format(path, text) == StructureFormat::Mmcif ? parse_mmcif(text, "") : parse_pdb(text, ""))
          .atoms.size();
  std::size_t atoms = 0;
  for (auto _ : state) {
    const Molecule molecule = read_molecule(path, {});
    atoms = molecule.atoms.size();
    benchmark::DoNotOptimize(molecule.atoms.data());
    benchmark::ClobberMemory();
  }
  state.counters["atoms"] = static_cast<double>(atoms);
  state.counters["atoms/s"] = benchmark::Counter(static_cast<double>(atoms), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["records/s"] =
      benchmark::Counter(static_cast<double>(records), benchmark::Counter::kIsIterationInvariantRate);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text.size()));
}

// Parsing alone (text already in memory): separates the tokenizer from file reading and inflating.
void BM_ParseText(benchmark::State& state, const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) return skip(state, "no " + path.string());
  using namespace nano::structure;
  const std::string text = read_structure_text(path);
  const StructureFormat format = detect_structure_format(path, text);
  std::size_t records = 0;
  for (auto _ : state) {
    const ParsedStructure parsed = format == StructureFormat::Mmcif ? parse_mmcif(text, "") : parse_pdb(text, "");
    records = parsed.atoms.size();
    benchmark::DoNotOptimize(parsed.atoms.data());
    benchmark::ClobberMemory();
  }
  state.counters["records/s"] =
      benchmark::Counter(static_cast<double>(records), benchmark::Counter::kIsIterationInvariantRate);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text.size()));
}

const std::filesystem::path kBiopythonPdb = "/usr/share/doc/python-biopython-doc/Tests/PDB";

// 6vxx: the largest in-repo file (23,694 atoms, gzipped); 4hhb: plain PDB with HETATM and water;
// 5x29: NMR-derived with hydrogens; popc_bilayer: many small residues; 2BEG: 10-model NMR mmCIF.
BENCHMARK_CAPTURE(BM_ReadMolecule, spike_6vxx_pdb_gz, structure_path("6vxx.pdb.gz"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadMolecule, haemoglobin_4hhb_pdb, structure_path("4hhb.pdb"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadMolecule, envelope_5x29_pdb, structure_path("5x29.pdb"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadMolecule, popc_bilayer_pdb_gz, structure_path("popc_bilayer.pdb.gz"))
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ReadMolecule, biopython_2BEG_cif_gz, kBiopythonPdb / "2BEG.cif.gz")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ParseText, haemoglobin_4hhb_pdb, structure_path("4hhb.pdb"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ParseText, biopython_2BEG_cif, kBiopythonPdb / "2BEG.cif.gz")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace nano::bench

BENCHMARK_MAIN();
