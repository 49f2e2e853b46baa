#include "bake/tiles/tiling_recipe.hpp"
#include "bake/tiles/wang_colouring.hpp"
#include "common/error.hpp"

#include <gtest/gtest.h>

#include <set>

namespace nano::tiles {
namespace {

TEST(WangColouring, CompleteSetsHoldEveryColourCombinationOnce) {
  for (int dims : {2, 3})
    for (int colours : {1, 2, 3}) {
      const WangColouring w = make_complete_colouring(dims, colours);
      size_t expected = 1;
      for (int i = 0; i < 2 * dims; ++i) expected *= colours;
      ASSERT_EQ(w.tile_count(), expected);
      std::set<SideColours> seen;
      for (uint32_t t = 0; t < w.tile_count(); ++t) {
        seen.insert(w.tiles[t]);
        EXPECT_EQ(w.complete_index(w.tiles[t]), t);
        for (int a = 0; a < 3; ++a)
          for (int s = 0; s < 2; ++s) EXPECT_LT(w.tiles[t][a][s], a < dims ? colours : 1);
      }
      EXPECT_EQ(seen.size(), expected);
    }
  EXPECT_EQ(make_complete_colouring(2, 2).tile_count(), 16u);
}

TEST(WangColouring, VariantSetsCoverEveryIncomingTripleWithUniformOutgoingColours) {
  const WangColouring w = make_variant_colouring(3, 2, 2, 5);
  ASSERT_EQ(w.tile_count(), 16u);
  for (uint32_t combo = 0; combo < 8; ++combo) {
    const std::array<uint8_t, 3> in{uint8_t(combo & 1), uint8_t((combo >> 1) & 1), uint8_t((combo >> 2) & 1)};
    std::array<std::array<int, 2>, 3> out{};
    for (uint32_t k = 0; k < 2; ++k) {
      const SideColours& c = w.tiles[w.variant_index(in, k)];
      for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(c[a][0], in[a]);
        ++out[a][c[a][1]];
      }
    }
    for (int a = 0; a < 3; ++a) EXPECT_EQ(out[a][0], 1) << "each outgoing colour once per incoming triple";
  }
  EXPECT_THROW(make_variant_colouring(3, 2, 0, 1), InputError);
  EXPECT_THROW(make_complete_colouring(4, 2), InputError);
  EXPECT_THROW(make_complete_colouring(3, 7), InputError);  // 7^6 tiles
}

// Neighbours agree on every shared side, including across the wrap when periodic.
void expect_matching(const WangColouring& w, const TilingRecipe& r) {
  for (int k = 0; k < r.size[2]; ++k)
    for (int j = 0; j < r.size[1]; ++j)
      for (int i = 0; i < r.size[0]; ++i) {
        const std::array<int, 3> cell{i, j, k};
        ASSERT_LT(r.at(i, j, k), w.tile_count());
        for (int a = 0; a < w.dims; ++a) {
          std::array<int, 3> next = cell;
          if (++next[a] == r.size[a]) {
            if (!r.periodic) continue;
            next[a] = 0;
          }
          ASSERT_EQ(w.tiles[r.at(i, j, k)][a][1], w.tiles[r.at(next[0], next[1], next[2])][a][0])
              << "cell " << i << "," << j << "," << k << " axis " << a;
        }
      }
}

TEST(TilingRecipe, NeighboursShareSideColoursForAllKindsOfSets) {
  for (uint64_t seed : {1u, 2u, 3u, 99u}) {
    const WangColouring squares = make_complete_colouring(2, 2);
    const WangColouring cubes = make_complete_colouring(3, 2);
    const WangColouring subset = make_variant_colouring(3, 2, 2, seed);
    for (bool periodic : {false, true}) {
      expect_matching(squares, make_tiling_recipe(squares, {6, 6, 1}, seed, periodic));
      expect_matching(squares, make_tiling_recipe(squares, {5, 3, 9}, seed, periodic));
      expect_matching(cubes, make_tiling_recipe(cubes, {4, 5, 3}, seed, periodic));
    }
    expect_matching(subset, make_tiling_recipe(subset, {4, 4, 4}, seed, false));
    expect_matching(make_complete_colouring(2, 3), make_tiling_recipe(make_complete_colouring(2, 3), {7, 7, 1}, seed, true));
  }
}

TEST(TilingRecipe, DeterministicForASeedAndDifferentAcrossSeeds) {
  const WangColouring w = make_complete_colouring(2, 2);
  EXPECT_EQ(make_tiling_recipe(w, {20, 20, 1}, 4, false).cells, make_tiling_recipe(w, {20, 20, 1}, 4, false).cells);
  EXPECT_NE(make_tiling_recipe(w, {20, 20, 1}, 4, false).cells, make_tiling_recipe(w, {20, 20, 1}, 5, false).cells);
  const WangColouring v = make_variant_colouring(3, 2, 2, 4);
  EXPECT_EQ(make_tiling_recipe(v, {5, 5, 5}, 4, false).cells, make_tiling_recipe(v, {5, 5, 5}, 4, false).cells);
  EXPECT_NE(make_tiling_recipe(v, {5, 5, 5}, 4, false).cells, make_tiling_recipe(v, {5, 5, 5}, 6, false).cells);
}

// Edge-first recipes are local: a cell depends only on its own faces' hashes, so a smaller recipe
// is exactly the corner of a larger one.
TEST(TilingRecipe, HashedRecipesAreLocalPerCell) {
  const WangColouring w = make_complete_colouring(3, 2);
  const TilingRecipe small = make_tiling_recipe(w, {3, 4, 2}, 8, false);
  const TilingRecipe large = make_tiling_recipe(w, {9, 7, 5}, 8, false);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 3; ++i) EXPECT_EQ(small.at(i, j, k), large.at(i, j, k));
}

// Over a large recipe every tile occurs about equally often (uniform face colours), which is what
// the density bookkeeping of the tile generator assumes.
TEST(TilingRecipe, TilesOccurAboutEquallyOften) {
  for (const WangColouring& w : {make_complete_colouring(2, 2), make_variant_colouring(3, 2, 2, 3)}) {
    const TilingRecipe r = make_tiling_recipe(w, w.dims == 2 ? std::array<int, 3>{128, 128, 1} : std::array<int, 3>{26, 26, 24}, 17, false);
    std::vector<int> count(w.tile_count(), 0);
    for (uint32_t t : r.cells) ++count[t];
    const double mean = double(r.cells.size()) / w.tile_count();
    for (int c : count) EXPECT_NEAR(c, mean, 0.1 * mean);
  }
}

TEST(TilingRecipe, RejectsBadRequests) {
  const WangColouring w = make_complete_colouring(2, 2);
  EXPECT_THROW(make_tiling_recipe(w, {0, 4, 1}, 1, false), InputError);
  EXPECT_THROW(make_tiling_recipe(w, {1 << 21, 1, 1}, 1, false), InputError);
  EXPECT_THROW(make_tiling_recipe(make_variant_colouring(3, 2, 2, 1), {4, 4, 4}, 1, true), InputError);
}

}  // namespace
}  // namespace nano::tiles
