// PackageView: every span is the section's records, and bounding radii come from the atoms.
#include <cmath>

#include <gtest/gtest.h>

#include "format/package_view.hpp"
#include "sample_scene.hpp"

namespace nano::format::test {
namespace {

TEST(PackageView, SpansAreTheSectionsAsWritten) {
  SampleScene s = make_sample_scene();
  const Package p = Package::from_bytes(build(s, Compression::zstd_if_smaller));
  const PackageView v(p);
  EXPECT_EQ(v.molecules.size(), s.molecules.size());
  EXPECT_EQ(v.atoms.size(), s.atoms.size());
  EXPECT_EQ(v.tiles2d.size(), s.tiles2d.size());
  EXPECT_EQ(v.tiles3d.size(), s.tiles3d.size());
  EXPECT_EQ(v.triangles.size(), s.triangles.size());
  EXPECT_EQ(v.occupancy.size(), s.occupancy.size());
  EXPECT_EQ(v.mask_words.size(), s.mask_words.size());
  EXPECT_EQ(v.compartment_instances.size(), s.compartment_instances.size());
  ASSERT_FALSE(v.atoms.empty());
  EXPECT_EQ(v.atoms.back().centre_radius, s.atoms.back().centre_radius);
}

// The sample's 2×2 membrane recipe is the checkerboard [[0, 1], [1, 0]] of tiles: any cell, negative
// ones too, reads the entry at its coordinates modulo 2, whatever its z.
TEST(PackageView, RecipeCellsWrapInEveryDirection) {
  const Package p = Package::from_bytes(build(make_sample_scene(), Compression::none));
  const PackageView v(p);
  const std::uint32_t checkerboard[2][2] = {{0, 1}, {1, 0}};  // [b mod 2][a mod 2]
  for (std::int64_t a = -5; a <= 5; ++a)
    for (std::int64_t b = -5; b <= 5; ++b)
      EXPECT_EQ(v.recipe_cell(0, a, b, a + b), checkerboard[(b % 2 + 2) % 2][(a % 2 + 2) % 2]) << a << "," << b;
  EXPECT_EQ(v.recipe_cell(1, 7, -3, -1), 0u);  // the 1×1×2 soluble recipe lists tile 0 twice
}

// The sample drops slot 0 instance 1 and slot 4 instance 0 of triangle 1, slot 8 instance 1 of
// triangle 3: exactly those keys, on exactly those triangles.
TEST(PackageView, DroppedMembraneCopiesAreFoundPerTriangle) {
  const Package p = Package::from_bytes(build(make_sample_scene(), Compression::zstd_if_smaller));
  const PackageView v(p);
  const auto key = [](std::uint32_t slot, std::uint32_t instance) { return (slot << 16) | instance; };
  int found = 0;
  for (std::uint32_t t = 0; t < 4; ++t)
    for (std::uint32_t slot = 0; slot < 9; ++slot)
      for (std::uint32_t m = 0; m < 2; ++m) found += v.membrane_copy_listed(t, key(slot, m));
  EXPECT_EQ(found, 3);
  EXPECT_TRUE(v.membrane_copy_listed(1, key(0, 1)));
  EXPECT_TRUE(v.membrane_copy_listed(1, key(4, 0)));
  EXPECT_TRUE(v.membrane_copy_listed(3, key(8, 1)));
  EXPECT_FALSE(v.membrane_copy_listed(0, key(0, 1)));  // another triangle's key
  SampleScene none = make_sample_scene();
  none.triangle_drops.clear();
  none.dropped_copies.clear();
  const Package q = Package::from_bytes(build(none));
  EXPECT_FALSE(PackageView(q).membrane_copy_listed(1, key(0, 1)));
}

TEST(PackageView, BoundingRadiusIsTheFarthestAtomSurfaceFromTheOrigin) {
  SampleScene s = make_sample_scene();
  // Type 0: atoms at known places; the farthest surface is |(3, 4, 0)| + 1.5 = 6.5 Å.
  ASSERT_GE(s.molecules[0].atom_count, 2u);
  const std::uint32_t a = s.molecules[0].first_atom;
  for (std::uint32_t k = 0; k < s.molecules[0].atom_count; ++k) s.atoms[a + k].centre_radius = {0.5f, 0, 0, 1.0f};
  s.atoms[a + 1].centre_radius = {3, 4, 0, 1.5f};
  const Package p = Package::from_bytes(build(s, Compression::none));
  const std::vector<double> radii = PackageView(p).atom_bounding_radii();
  ASSERT_EQ(radii.size(), s.molecules.size());
  EXPECT_DOUBLE_EQ(radii[0], 6.5);
  for (std::size_t t = 0; t < radii.size(); ++t) EXPECT_TRUE(std::isfinite(radii[t]) && radii[t] >= 0);
}

}  // namespace
}  // namespace nano::format::test

namespace nano::format::test {
namespace {

TEST(PackageView, InstanceTransformReadsRowsIntoColumnMajorDouble) {
  gpu::CompartmentInstance ci{};
  // Rows of [L | T]: L = [[1,2,3],[4,5,6],[7,8,10]], T = (11, 12, 13).
  ci.transform[0] = {1, 2, 3, 11};
  ci.transform[1] = {4, 5, 6, 12};
  ci.transform[2] = {7, 8, 10, 13};
  const InstanceTransform t = instance_transform(ci);
  const glm::dvec3 p(1, -1, 2);
  const glm::dvec3 world = t.linear * p + t.translation;
  EXPECT_DOUBLE_EQ(world.x, 1 - 2 + 6 + 11);
  EXPECT_DOUBLE_EQ(world.y, 4 - 5 + 12 + 12);
  EXPECT_DOUBLE_EQ(world.z, 7 - 8 + 20 + 13);
}

}  // namespace
}  // namespace nano::format::test
