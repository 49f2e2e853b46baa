#include "bake/grid/soluble_masks.hpp"

#include <random>

#include <gtest/gtest.h>

#include "bake/mesh/rbc_mesh.hpp"
#include "bake/mesh/sphere_mesh.hpp"
#include "common/error.hpp"
#include "tests/grid/grid_oracles.hpp"

namespace nano::grid {
namespace {

std::vector<CubeContents> random_cubes(int count, int molecules, double box_size, double max_radius, std::uint32_t types,
                                       unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(0.0, box_size), rad(0.0, max_radius);
  std::uniform_int_distribution<std::uint32_t> type(0, types - 1);
  std::vector<CubeContents> cubes(count);
  for (int c = 0; c < count; ++c)
    for (int m = 0; m < molecules + 7 * c; ++m)  // different sizes, some over 32 bits
      cubes[c].push_back({{pos(rng), pos(rng), pos(rng)}, rad(rng), type(rng)});
  return cubes;
}

// A hash recipe, as the edge-first Wang recipes are: no structure the code could exploit.
CubeRecipe hash_recipe(std::uint32_t cubes) {
  return [cubes](const glm::ivec3& b) {
    std::uint32_t h = static_cast<std::uint32_t>(b.x) * 73856093u ^ static_cast<std::uint32_t>(b.y) * 19349663u ^
                      static_cast<std::uint32_t>(b.z) * 83492791u;
    h ^= h >> 13;
    return (h * 0x5bd1e995u >> 7) % cubes;
  };
}

bool bit(std::span<const std::uint32_t> mask, std::size_t m) { return mask[m / 32] >> (m % 32) & 1u; }

// Every molecule of `sample_every`-th BOUNDARY box (and of INSIDE boxes) against brute force.
void check_against_brute_force(const mesh::ProxyMesh& m, double S, double h, double max_radius, std::size_t sample_every) {
  const MeshSurface surface(m);
  const double clearance = h + max_radius;
  const BoxOccupancy occ = classify_boxes(surface, make_core_grid(m, S), clearance);
  const std::vector<CubeContents> cubes = random_cubes(4, 30, S, max_radius, 3, 11);
  const CubeRecipe recipe = hash_recipe(4);
  const KeepMasks masks = compute_keep_masks(surface, occ, cubes, recipe, h, 2);
  ASSERT_EQ(masks.boundary_boxes.size(), occ.boundary);
  EXPECT_TRUE(std::is_sorted(masks.boundary_boxes.begin(), masks.boundary_boxes.end()));
  EXPECT_EQ(compute_keep_masks(surface, occ, cubes, recipe, h, 1).words, masks.words);  // thread-independent

  std::uint64_t kept = 0, dropped = 0, checked = 0, ambiguous = 0, inside_checked = 0;
  for (BoxIndex i = 0; i < occ.grid.box_count(); ++i) {
    const glm::ivec3 b = occ.grid.box_at(i);
    const std::span<const std::uint32_t> mask = masks.mask_of(i);
    if (occ.classes[i] != BoxClass::boundary) {
      EXPECT_TRUE(mask.empty());
      // Implicitly kept molecules of (a sample of) INSIDE boxes satisfy the rule too.
      if (occ.classes[i] == BoxClass::inside && i % (7 * sample_every) == 0)
        for (const CubeMolecule& mol : cubes[recipe(b)]) {
          const glm::dvec3 p = occ.grid.box_min(b) + mol.centre;
          EXPECT_TRUE(oracle::mesh_contains(m, p));
          EXPECT_GE(oracle::mesh_distance(m, p), mol.radius + h);
          ++inside_checked;
        }
      continue;
    }
    const CubeContents& cube = cubes[recipe(b)];
    ASSERT_EQ(mask.size(), (cube.size() + 31) / 32);
    for (std::size_t n = 0; n < cube.size(); ++n) (bit(mask, n) ? kept : dropped) += 1;
    if ((checked++) % sample_every != 0) continue;
    for (std::size_t n = 0; n < cube.size(); ++n) {
      const glm::dvec3 p = occ.grid.box_min(b) + cube[n].centre;
      const double d = oracle::mesh_distance(m, p), need = cube[n].radius + h;
      if (std::abs(d - need) < 1e-6 * S) { ++ambiguous; continue; }  // rounding decides; either is fine
      const bool expected = d >= need && oracle::mesh_contains(m, p);
      EXPECT_EQ(bit(mask, n), expected) << "box " << i << " molecule " << n << " d " << d << " need " << need;
    }
  }
  EXPECT_EQ(kept, masks.kept);
  EXPECT_EQ(dropped, masks.dropped);
  EXPECT_GT(masks.kept, 0u);
  EXPECT_GT(masks.dropped, 0u);
  EXPECT_LT(ambiguous, 3u);
  EXPECT_GT(inside_checked, 0u);
  EXPECT_EQ(masks.bytes(), 4 * (masks.boundary_boxes.size() + masks.word_offsets.size() + masks.words.size()));

  // Represented copies against explicit enumeration of every box's molecules.
  std::vector<std::uint64_t> expected(3, 0);
  for (BoxIndex i = 0; i < occ.grid.box_count(); ++i) {
    if (occ.classes[i] == BoxClass::outside) continue;
    const CubeContents& cube = cubes[recipe(occ.grid.box_at(i))];
    for (std::size_t n = 0; n < cube.size(); ++n)
      if (occ.classes[i] == BoxClass::inside || bit(masks.mask_of(i), n)) ++expected[cube[n].type];
  }
  EXPECT_EQ(represented_copies(occ, cubes, recipe, masks), expected);
}

TEST(SolubleMasks, SphereAgainstBruteForce) { check_against_brute_force(mesh::make_sphere_mesh(500, 3000.0), 400.0, 60.0, 80.0, 1); }
TEST(SolubleMasks, RbcAgainstBruteForce) { check_against_brute_force(mesh::make_rbc_mesh(600), 2000.0, 300.0, 400.0, 8); }

TEST(SolubleMasks, MaskOfOtherBoxesIsEmpty) {
  KeepMasks masks;
  masks.boundary_boxes = {3, 9};
  masks.word_offsets = {0, 1, 3};
  masks.words = {5u, 6u, 7u};
  EXPECT_TRUE(masks.mask_of(0).empty());
  EXPECT_TRUE(masks.mask_of(4).empty());
  EXPECT_TRUE(masks.mask_of(10).empty());
  ASSERT_EQ(masks.mask_of(3).size(), 1u);
  EXPECT_EQ(masks.mask_of(3)[0], 5u);
  ASSERT_EQ(masks.mask_of(9).size(), 2u);
  EXPECT_EQ(masks.mask_of(9)[1], 7u);
  EXPECT_EQ(masks.bytes(), 4u * (2 + 3 + 3));
}

TEST(SolubleMasks, BadInputThrows) {
  const mesh::ProxyMesh m = mesh::make_sphere_mesh(200, 1000.0);
  const MeshSurface surface(m);
  const BoxOccupancy occ = classify_boxes(surface, make_core_grid(m, 200.0), 100.0);
  const CubeRecipe zero = [](const glm::ivec3&) { return 0u; };
  const std::vector<CubeContents> ok = {{{{10, 10, 10}, 50.0, 0}}};
  EXPECT_NO_THROW(compute_keep_masks(surface, occ, ok, zero, 50.0));
  EXPECT_THROW(compute_keep_masks(surface, occ, ok, zero, 50.1), InputError);  // 50.1 + 50 > clearance 100
  EXPECT_THROW(compute_keep_masks(surface, occ, ok, zero, -1.0), InputError);
  EXPECT_THROW(compute_keep_masks(surface, occ, {}, zero, 0.0), InputError);
  EXPECT_THROW(compute_keep_masks(surface, occ, {{{{200, 10, 10}, 1.0, 0}}}, zero, 0.0), InputError);  // centre = S: not in [0, S)
  EXPECT_THROW(compute_keep_masks(surface, occ, {{{{-1, 10, 10}, 1.0, 0}}}, zero, 0.0), InputError);
  EXPECT_THROW(compute_keep_masks(surface, occ, {{{{1, 10, 10}, -1.0, 0}}}, zero, 0.0), InputError);
  EXPECT_THROW(compute_keep_masks(surface, occ, ok, [](const glm::ivec3&) { return 1u; }, 0.0), InputError);
  const KeepMasks masks = compute_keep_masks(surface, occ, ok, zero, 0.0);
  EXPECT_THROW(represented_copies(occ, ok, [](const glm::ivec3&) { return 2u; }, masks), InputError);
  EXPECT_THROW(represented_copies(occ, ok, zero, KeepMasks{}), InputError);
}

}  // namespace
}  // namespace nano::grid
