#include "bake/tiles/wang_sets.hpp"
#include "common/error.hpp"
#include "tests/tiles/tiles_test_support.hpp"

#include <gtest/gtest.h>

namespace nano::tiles {
namespace {

constexpr float kCubeEdge = 150.f;

SolubleCubeRequest haemoglobin_request(uint64_t seed) {
  SolubleCubeRequest r;
  r.types = {test::make_haemoglobin()};
  r.edge = kCubeEdge;
  r.molecules = {{0, copies_per_um3_from_millimolar(5.0)}};
  r.seed = seed;
  return r;
}

TEST(SolubleCubes, MillimolarConversion) {
  EXPECT_NEAR(copies_per_um3_from_millimolar(5.0), 3.011e6, 1e3);  // BIOLOGY.md: ~3.0e6 per µm³
  EXPECT_DOUBLE_EQ(copies_per_um3_from_millimolar(0.0), 0.0);
}

class SolubleCubesSeeds : public testing::TestWithParam<uint64_t> {};

TEST_P(SolubleCubesSeeds, HaemoglobinAt5mMIsCollisionFreeInRandomTilings) {
  {
    const uint64_t seed = GetParam();
    const SolubleCubeRequest req = haemoglobin_request(seed);
    const WangSet set = make_soluble_cubes(req);
    ASSERT_EQ(set.tiles.size(), 16u);
    const TilingRecipe recipe = make_tiling_recipe(set.colouring, {4, 4, 4}, seed + 10, false);
    const test::ExplicitTiling tiling = test::instantiate(set, recipe, req.types);
    EXPECT_TRUE(tiling.ownership_ok);
    const test::ClosePair p = test::find_close_pair(tiling.atoms, 0.6f);
    EXPECT_FALSE(p.found) << "seed " << seed << ": atoms " << p.distance << " Å apart, limit " << p.limit;
    // Concentration over the explicit 4x4x4 block: within 10% of 5 mM.
    const double um3 = 64.0 * kCubeEdge * kCubeEdge * kCubeEdge * 1e-12;
    EXPECT_NEAR(tiling.copies / um3, req.molecules[0].copies_per_um3, 0.1 * req.molecules[0].copies_per_um3);
    EXPECT_NEAR(set.densities[0].achieved, req.molecules[0].copies_per_um3, 0.1 * req.molecules[0].copies_per_um3);
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, SolubleCubesSeeds, testing::Values(1u, 2u, 3u));

// Complete cube set (64 cubes), two molecule types, periodic recipe repeated across its wrap.
TEST(SolubleCubes, CompleteSetPeriodicMixtureIsCollisionFree) {
  SolubleCubeRequest req;
  req.types = {test::make_protein(), test::make_blob("small", 60, 8.f, 6.f, 5.f, 3)};
  req.edge = 110.f;
  req.variants = 0;
  req.molecules = {{0, 3.0 / (110e-4 * 110e-4 * 110e-4)}, {1, 20.0 / (110e-4 * 110e-4 * 110e-4)}};
  req.seed = 3;
  const WangSet set = make_soluble_cubes(req);
  ASSERT_EQ(set.tiles.size(), 64u);
  const TilingRecipe r = make_tiling_recipe(set.colouring, {2, 2, 2}, 3, true);
  TilingRecipe big = r;
  big.size = {4, 4, 4};
  big.cells.resize(64);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) big.cells[(k * 4 + j) * 4 + i] = r.at(i % 2, j % 2, k % 2);
  const test::ExplicitTiling tiling = test::instantiate(set, big, req.types);
  EXPECT_FALSE(test::find_close_pair(tiling.atoms, 0.6f).found);
  // Mean copies per cube over a large non-periodic tiling: within 10% of the request.
  const test::ExplicitTiling counts =
      test::instantiate(set, make_tiling_recipe(set.colouring, {20, 20, 20}, 4, false), req.types, false);
  for (int t = 0; t < 2; ++t)
    EXPECT_NEAR(counts.copies_per_type[t] / 8000.0, t == 0 ? 3.0 : 20.0, t == 0 ? 0.3 : 2.0);
}

// Copies near cube faces, edges and corners really straddle them (the corners are not left empty).
TEST(SolubleCubes, StraddlingCopiesFillFacesEdgesAndCorners) {
  const SolubleCubeRequest req = haemoglobin_request(3);
  const WangSet set = make_soluble_cubes(req);
  int near_corner = 0;
  for (const WangTile& t : set.tiles)
    for (const Instance& in : t.instances) {
      int near = 0;
      for (int a = 0; a < 3; ++a) near += std::min(in.position[a], kCubeEdge - in.position[a]) < 25.f;
      near_corner += near == 3;
    }
  EXPECT_GT(near_corner, 0);
  EXPECT_GT(set.max_overhang(), 10.f);
}

// Compact haemoglobin-like ellipsoids at 6 mM in 150 Å cubes: random sequential addition jams at
// ~84% (more than 10% short: an error), the densified set reaches the request. The oracle finds it
// collision-free at the generator's own clearance in an explicit tiling, and counts the request over
// a large one.
TEST(SolubleCubes, DensificationReachesWhatSequentialAdditionCannot) {
  SolubleCubeRequest req = haemoglobin_request(8);
  req.molecules[0].copies_per_um3 = copies_per_um3_from_millimolar(6.0);
  SolubleCubeRequest plain = req;
  plain.budget.relaxation_rounds = 0;
  EXPECT_THROW(make_soluble_cubes(plain), InputError);

  const WangSet set = make_soluble_cubes(req);
  const double wanted = req.molecules[0].copies_per_um3;
  EXPECT_GE(set.densities[0].achieved, 0.98 * wanted);
  const test::ExplicitTiling tiling =
      test::instantiate(set, make_tiling_recipe(set.colouring, {3, 3, 3}, 9, false), req.types);
  EXPECT_TRUE(tiling.ownership_ok);
  const test::ClosePair p = test::find_close_pair(tiling.atoms, 0.999f);
  EXPECT_FALSE(p.found) << "atoms " << p.distance << " Å apart, limit " << p.limit;
  const TilingRecipe large = make_tiling_recipe(set.colouring, {16, 16, 16}, 10, false);
  const test::ExplicitTiling counts = test::instantiate(set, large, req.types, false);
  const double um3 = 4096.0 * kCubeEdge * kCubeEdge * kCubeEdge * 1e-12;
  EXPECT_NEAR(counts.copies / um3, wanted, 0.04 * wanted);
}

TEST(SolubleCubes, SameSeedSameBytesOtherSeedOtherCubes) {
  SolubleCubeRequest req = haemoglobin_request(4);
  req.types[0] = test::make_protein();
  const WangSet a = make_soluble_cubes(req), b = make_soluble_cubes(req);
  req.seed = 5;
  const WangSet c = make_soluble_cubes(req);
  EXPECT_EQ(test::set_bytes(a), test::set_bytes(b));
  EXPECT_NE(test::set_bytes(a), test::set_bytes(c));
}

TEST(SolubleCubes, ImpossibleConcentrationThrowsNamingTheMolecule) {
  SolubleCubeRequest req = haemoglobin_request(1);
  req.types[0] = test::make_protein();
  req.edge = 100.f;
  req.molecules[0].copies_per_um3 = 40.0 / 1e-6;  // 40 copies of a 50 Å blob per 100 Å cube
  req.budget.max_consecutive_failures = 300;
  try {
    make_soluble_cubes(req);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "protein");
    EXPECT_NE(e.rule().find("best achieved"), std::string::npos);
  }
  SolubleCubeRequest small = haemoglobin_request(1);
  small.edge = 60.f;  // smaller than a haemoglobin
  EXPECT_THROW(make_soluble_cubes(small), InputError);
  small = haemoglobin_request(1);
  small.variants = -1;
  EXPECT_THROW(make_soluble_cubes(small), InputError);
}

}  // namespace
}  // namespace nano::tiles
