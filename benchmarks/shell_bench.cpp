// Adaptive shell offsets (bake/shell): per triangle +h/−h/side estimated from the molecules it owns,
// verified against the float prism and grown — the per-compartment membrane stage of the baker —
// over the virion's cube-sphere (bake/mesh make_sphere_mesh, radius 450 Å) at several triangle
// counts. The membrane and its Wang set are the same at every count (tile_inputs.hpp, generated
// once, untimed), so the molecules owned stay ~constant and the per-triangle overhead shows.
//   BM_ShellOffsets   compute_shell_offsets; args: requested triangles (the cube-sphere rounds to
//                     12 n²: 1452, 5808, 12288), threads
//   BM_MembraneMapping  building the MembraneMapping the offsets read (charts, seams, replication
//                     areas): paid once per compartment before the offsets
//   BM_MembranePruning  prune_membrane checking every copy on the surface (a whole cell's membrane
//                     is mostly this: each copy's ~40 neighbours tested atom by atom); args: triangles,
//                     threads. Counters: copies/s, atom_pairs (atom pairs of two copies measured), clashing_pairs.
// Counters: triangles (actual), triangles/s, molecules/s (owned molecules checked per second).
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "benchmarks/tile_inputs.hpp"
#include "bake/shell/membrane_mapping.hpp"
#include "bake/shell/membrane_pruning.hpp"
#include "bake/shell/shell_offsets.hpp"
#include "bake/tiles/tiling_recipe.hpp"

namespace nano::bench {
namespace {

struct Membrane {
  tiles::MembraneTileRequest request;
  tiles::WangSet set;
};

const Membrane& membrane() {
  static const Membrane m = [] {
    Membrane r{virion_membrane_request(), {}};
    r.set = tiles::make_membrane_tiles(r.request);
    return r;
  }();
  return m;
}

// A mesh with its recipe and mapping, built once per triangle count (the mapping references them).
struct Compartment {
  mesh::ProxyMesh mesh;
  double k = 0.0;
  tiles::TilingRecipe recipe;
  std::unique_ptr<shell::MembraneMapping> mapping;
};

const Compartment& compartment(int triangles) {
  static std::map<int, std::unique_ptr<Compartment>> cache;
  std::unique_ptr<Compartment>& c = cache[triangles];
  if (c) return *c;
  const Membrane& m = membrane();
  c = std::make_unique<Compartment>();
  c->mesh = mesh::make_sphere_mesh(triangles, kVirionRadius);
  c->k = mesh::uv_scale(c->mesh);
  // As bake/scene_bake/wang_bake.cpp membrane_recipe: periodic, covering UV [0,1]², ≤ 1024 cells.
  const int cells = std::clamp(static_cast<int>(std::ceil(c->k / m.set.edge)), 1, 1024);
  c->recipe = tiles::make_tiling_recipe(m.set.colouring, {cells, cells, 1}, 7, /*periodic=*/true);
  c->mapping = std::make_unique<shell::MembraneMapping>(c->mesh, m.set, c->recipe, c->k, m.request.types);
  return *c;
}

void count_triangles(benchmark::State& state, std::size_t triangles) {
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["triangles/s"] =
      benchmark::Counter(static_cast<double>(triangles), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_ShellOffsets(benchmark::State& state) {
  const Compartment& c = compartment(static_cast<int>(state.range(0)));
  const std::vector<tiles::MoleculeType>& types = membrane().request.types;
  std::size_t owned = 0;
  for (auto _ : state) {
    const shell::ShellResult result = shell::compute_shell_offsets(*c.mapping, types, static_cast<int>(state.range(1)));
    owned = result.stats.owned_molecules;
    benchmark::DoNotOptimize(result.offsets.data());
    benchmark::ClobberMemory();
  }
  count_triangles(state, c.mapping->triangle_count());
  state.counters["molecules/s"] = benchmark::Counter(static_cast<double>(owned), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ShellOffsets)->ArgNames({"triangles", "threads"})
    ->Args({1452, 1})->Args({6000, 1})->Args({12000, 1})->Args({12000, 2})
    ->Unit(benchmark::kMillisecond)->UseRealTime();  // real time: the 2-thread case runs on std::threads

void BM_MembraneMapping(benchmark::State& state) {
  const Compartment& c = compartment(static_cast<int>(state.range(0)));
  const Membrane& m = membrane();
  for (auto _ : state) {
    const shell::MembraneMapping mapping(c.mesh, m.set, c.recipe, c.k, m.request.types);
    benchmark::DoNotOptimize(&mapping.triangle(0));
    benchmark::ClobberMemory();
  }
  count_triangles(state, c.mesh.triangles.size());
}
BENCHMARK(BM_MembraneMapping)->ArgName("triangles")->Arg(1452)->Arg(12000)->Unit(benchmark::kMillisecond);

void BM_MembranePruning(benchmark::State& state) {
  const Compartment& c = compartment(static_cast<int>(state.range(0)));
  shell::PruningSettings settings;
  settings.whole_surface = true;
  shell::PrunedMembrane pruned;
  for (auto _ : state) {
    pruned = shell::prune_membrane(*c.mapping, c.mesh, membrane().request.types, settings, static_cast<int>(state.range(1)));
    benchmark::DoNotOptimize(pruned.dropped.data());
    benchmark::ClobberMemory();
  }
  state.counters["copies/s"] =
      benchmark::Counter(static_cast<double>(pruned.checked_copies), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["atom_pairs"] = static_cast<double>(pruned.atom_pairs);
  state.counters["clashing_pairs"] = static_cast<double>(pruned.clashing_pairs);
}
BENCHMARK(BM_MembranePruning)->ArgNames({"triangles", "threads"})->Args({1452, 1})->Args({1452, 2})
    ->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace nano::bench

BENCHMARK_MAIN();
