// Tile-set and recipe generation (bake/tiles), the stages bake/scene_bake/wang_bake.cpp runs per
// membrane and per soluble, on molecules read from data/structures with fixed seeds:
//   BM_MembraneSquares  make_membrane_tiles: 16 squares of 200 Å, the virion's M protein plus a
//                       lipid fill on both leaflets, packed for its curved mesh (tile_inputs.hpp).
//   BM_SolubleCubes     make_soluble_cubes: 16 variant cubes (2 colours x 2 variants), 250 Å,
//                       haemoglobin 4hhb at 2 and 5 mM (the latter needs the relaxation pass).
//   BM_CopiesCollide    the atom-level pair test every dart of the packer pays for, on two
//                       haemoglobins at poses whose bounding spheres overlap (the only pairs it tests).
//   BM_Recipe           make_tiling_recipe over the lattice sizes the baker uses (up to 1024² cells
//                       for a membrane's UV square, 64³ for a core grid), complete and variant sets.
// Counters: tiles/s and molecules/s (copies placed in the set), pairs/s, cells/s (items).
#include <array>
#include <string>
#include <vector>

#include "benchmarks/tile_inputs.hpp"
#include "bake/tiles/collision_shape.hpp"
#include "bake/tiles/rotation_sampling.hpp"
#include "bake/tiles/tile_random.hpp"
#include "bake/tiles/tiling_recipe.hpp"

namespace nano::bench {
namespace {

// Read once per process: reading is structure_bench's subject, not this file's.
const tiles::MoleculeType& haemoglobin() {
  static const tiles::MoleculeType type = read_tile_molecule("4hhb.pdb", "haemoglobin_4hhb");
  return type;
}

void count_set(benchmark::State& state, const tiles::WangSet& set) {
  std::size_t copies = 0;
  for (const tiles::WangTile& tile : set.tiles) copies += tile.instances.size();
  state.counters["tiles/s"] =
      benchmark::Counter(static_cast<double>(set.tiles.size()), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["molecules/s"] =
      benchmark::Counter(static_cast<double>(copies), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["molecules"] = static_cast<double>(copies);
}

void BM_MembraneSquares(benchmark::State& state) {
  const tiles::MembraneTileRequest request = virion_membrane_request();
  tiles::WangSet set;
  for (auto _ : state) {
    set = tiles::make_membrane_tiles(request);
    benchmark::DoNotOptimize(set.tiles.data());
    benchmark::ClobberMemory();
  }
  count_set(state, set);
}
BENCHMARK(BM_MembraneSquares)->Unit(benchmark::kMillisecond);

void BM_SolubleCubes(benchmark::State& state) {
  tiles::SolubleCubeRequest request;
  request.types = {haemoglobin()};
  request.edge = 250.f;
  request.colours = 2;
  request.variants = 2;
  request.molecules = {{0, tiles::copies_per_um3_from_millimolar(static_cast<double>(state.range(0)))}};
  request.seed = 7;
  tiles::WangSet set;
  for (auto _ : state) {
    set = tiles::make_soluble_cubes(request);
    benchmark::DoNotOptimize(set.tiles.data());
    benchmark::ClobberMemory();
  }
  count_set(state, set);
}
// 2 mM fits by random sequential addition alone; data/virion.json's 5 mM needs the relaxation pass.
BENCHMARK(BM_SolubleCubes)->ArgName("mM")->Arg(2)->Arg(5)->Unit(benchmark::kMillisecond);

void BM_CopiesCollide(benchmark::State& state) {
  const tiles::CollisionShape shape(haemoglobin());
  // Poses of b around a at 0.5 to 1.0 x (r_a + r_b): from deep overlap (early exit on the first
  // clashing atom) to grazing contact (most atoms visited, usually no clash) — the packer's mix.
  struct PosePair {
    tiles::Pose a, b;
  };
  std::vector<PosePair> pairs;
  tiles::SplitMix64 rng(11);
  for (int i = 0; i < 256; ++i) {
    const glm::vec3 direction = tiles::uniform_rotation(rng) * glm::vec3(0.f, 0.f, 1.f);
    const float distance = static_cast<float>(rng.uniform(1.0, 2.0)) * shape.radius();
    pairs.push_back({{glm::vec3(0.f), glm::mat3_cast(tiles::uniform_rotation(rng))},
                     {distance * direction, glm::mat3_cast(tiles::uniform_rotation(rng))}});
  }
  const tiles::ClashRule rule;
  std::size_t i = 0, clashes = 0;
  for (auto _ : state) {
    const PosePair& p = pairs[i++ % pairs.size()];
    const bool clash = tiles::copies_collide(shape, p.a, shape, p.b, rule);
    benchmark::DoNotOptimize(clash);
    clashes += clash;
  }
  state.counters["clash_fraction"] = static_cast<double>(clashes) / static_cast<double>(state.iterations());
  state.counters["pairs/s"] = benchmark::Counter(1.0, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_CopiesCollide);

// Arguments: cells per axis, colours, variants (0 = complete set, periodic recipe), dims.
void BM_Recipe(benchmark::State& state) {
  const int cells = static_cast<int>(state.range(0));
  const int colours = static_cast<int>(state.range(1));
  const int variants = static_cast<int>(state.range(2));
  const int dims = static_cast<int>(state.range(3));
  const tiles::WangColouring colouring = variants == 0 ? tiles::make_complete_colouring(dims, colours)
                                                       : tiles::make_variant_colouring(dims, colours, variants, 3);
  const std::array<int, 3> size{cells, cells, dims == 3 ? cells : 1};
  for (auto _ : state) {
    const tiles::TilingRecipe recipe = tiles::make_tiling_recipe(colouring, size, 5, /*periodic=*/variants == 0);
    benchmark::DoNotOptimize(recipe.cells.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(size[0]) * size[1] * size[2]);
  state.SetLabel(std::to_string(colouring.tile_count()) + " tiles");
}
// Membrane UV squares: a small compartment and the kMaxRecipe2DCells cap.
BENCHMARK(BM_Recipe)->ArgNames({"cells", "colours", "variants", "dims"})
    ->Args({256, 2, 0, 2})->Args({1024, 2, 0, 2})->Args({1024, 3, 0, 2})
    // Core grids at the kMaxRecipe3DCells cap: complete (edge-first) and variant (scanline) cube sets.
    ->Args({64, 2, 0, 3})->Args({64, 2, 2, 3})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace nano::bench

BENCHMARK_MAIN();
