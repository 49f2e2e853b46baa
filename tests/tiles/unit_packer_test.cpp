#include "bake/tiles/unit_packer.hpp"
#include "tests/tiles/tiles_test_support.hpp"

#include <gtest/gtest.h>

namespace nano::tiles {
namespace {

// Single spheres of two sizes, packed directly (no front end), with 3 colours per side: the
// explicit tilings stay clear of overlaps at the packer's own clearance (oracle at 0.999 of it),
// and the reported mean density equals the mean over a large explicit tiling.
TEST(UnitPacker, SpheresIn2DAnd3DAreClearInEveryTilingAndCountedRight) {
  const std::vector<MoleculeType> types{{"big", {{{0, 0, 0}, 9.f}}, 9.f, {0, 0, 1}},
                                        {"small", {{{0, 0, 0}, 3.f}}, 3.f, {0, 0, 1}}};
  const std::vector<CollisionShape> shapes{CollisionShape(types[0]), CollisionShape(types[1])};
  for (int dims : {2, 3}) {
    const float edge = 60.f;
    const double measure = dims == 2 ? edge * edge : edge * edge * edge;
    std::vector<PlacementSpec> specs(2);
    specs[0].type = 0;
    specs[0].copies_per_volume = 2.0 / measure;
    specs[0].band = 9.01f;
    specs[1].type = 1;
    specs[1].copies_per_volume = 1e3 / measure;  // far more than fits: fill as far as possible
    specs[1].band = 3.01f;
    for (PlacementSpec& s : specs) s.uniform_rotation = dims == 3;
    const WangColouring colouring = make_complete_colouring(dims, dims == 2 ? 3 : 2);
    PackerSettings settings;
    settings.edge = edge;
    settings.clearance = 1.f;
    settings.seed = 21;
    settings.attempts_per_copy = 50;
    settings.max_consecutive_failures = 400;
    const PackedUnits packed = pack_wang_units(shapes, specs, colouring, settings);
    ASSERT_EQ(packed.tiles.size(), colouring.tile_count());
    WangSet set{dims, edge, colouring, packed.tiles, {}};
    const std::array<int, 3> small = dims == 2 ? std::array<int, 3>{6, 6, 1} : std::array<int, 3>{4, 4, 4};
    const test::ExplicitTiling t = test::instantiate(set, make_tiling_recipe(colouring, small, 5, false), types);
    EXPECT_TRUE(t.ownership_ok);
    EXPECT_FALSE(test::find_close_pair(t.atoms, 0.999f).found) << dims;
    const std::array<int, 3> large = dims == 2 ? std::array<int, 3>{90, 90, 1} : std::array<int, 3>{24, 24, 24};
    const TilingRecipe big = make_tiling_recipe(colouring, large, 6, false);
    const test::ExplicitTiling counts = test::instantiate(set, big, types, false);
    for (int s = 0; s < 2; ++s) {
      const double explicit_density = counts.copies_per_type[s] / (big.cells.size() * measure);
      EXPECT_NEAR(packed.achieved_per_volume[s], explicit_density, 0.05 * explicit_density) << dims << " " << s;
    }
    EXPECT_NEAR(packed.achieved_per_volume[0] * measure, 2.0, 0.1);
  }
}

TEST(UnitPacker, ComputeAtomBoundsCoversEveryAtom) {
  const std::vector<MoleculeType> types{test::make_lipid()};
  const std::vector<CollisionShape> shapes{CollisionShape(types[0])};
  WangTile tile;
  compute_atom_bounds(tile, shapes);
  EXPECT_EQ(tile.atoms_min, glm::vec3(0.f));
  EXPECT_EQ(tile.atoms_max, glm::vec3(0.f));
  tile.instances = {{0, {1, 2, 3}, glm::quat(1, 0, 0, 0)}, {0, {50, 2, 3}, glm::normalize(glm::quat(1, 1, 0, 0))}};
  compute_atom_bounds(tile, shapes);
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const Instance& in : tile.instances)
    for (const AtomSphere& a : types[0].atoms) {
      lo = glm::min(lo, in.position + test::rotate(in.rotation, a.centre) - a.radius);
      hi = glm::max(hi, in.position + test::rotate(in.rotation, a.centre) + a.radius);
    }
  EXPECT_NEAR(glm::length(tile.atoms_min - lo), 0.f, 1e-4f);
  EXPECT_NEAR(glm::length(tile.atoms_max - hi), 0.f, 1e-4f);
}

}  // namespace
}  // namespace nano::tiles
