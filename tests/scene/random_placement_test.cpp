#include "bake/scene/random_placement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "tests/scene/input_error_matchers.hpp"

namespace nano::scene {
namespace {

// Two compartments: "big" (radius 300 as passed in) and "small" (radius 100).
const std::vector<double> radii = {300.0, 100.0};
const NameRef big{"big", 0}, small{"small", 1};

SceneDescription scene_with(std::vector<InstanceEntry> instances) {
  SceneDescription s;
  s.source = "scene.json";
  s.compartments.resize(2);
  s.compartments[0].name = "big";
  s.compartments[1].name = "small";
  s.instances = std::move(instances);
  return s;
}

glm::dvec3 centre_of(const Matrix3x4& m) { return {m[0][3], m[1][3], m[2][3]}; }

const Box box{{-2000, -1000, 0}, {2000, 1000, 1500}};

// Dense enough that the gap matters: the copies' exclusion spheres (radius 350 for two small
// copies) cover about half of the room their centres have.
constexpr double gap = 150.0;
SceneDescription mixed_scene(std::uint64_t seed) {
  return scene_with({
      RandomPlacement{big, 5, box, seed, gap},
      // Doubled in size and placed explicitly: random copies must keep clear of radius 600.
      ExplicitInstance{big, translate_rotate_scale({0, 0, 700}, {0, 0, 1}, 0, 2.0)},
      RandomPlacement{small, 40, box, seed + 1, gap},
  });
}

TEST(RandomPlacement, DerivedSeedIsOneSplitMix64Step) {
  // splitmix64 from state 0 first yields 0xE220A8397B1DCDAF (the published reference value);
  // entry 0 mixes the scene seed with 0xD1B54A32D192ED03, so this scene seed gives state 0.
  EXPECT_EQ(derive_placement_seed(0xD1B54A32D192ED03ull, 0), 0xE220A8397B1DCDAFull);
  EXPECT_NE(derive_placement_seed(42, 0), derive_placement_seed(42, 1));
  EXPECT_NE(derive_placement_seed(42, 0), derive_placement_seed(43, 0));
}

TEST(RandomPlacement, ExpandedInstanceCount) {
  EXPECT_EQ(expanded_instance_count(mixed_scene(1)), 46u);
  EXPECT_EQ(expanded_instance_count(scene_with({})), 0u);
}

TEST(RandomPlacement, SameSeedSameTransformsOtherSeedOthers) {
  const auto a = expand_random_instances(mixed_scene(9), radii);
  const auto b = expand_random_instances(mixed_scene(9), radii);
  const auto c = expand_random_instances(mixed_scene(10), radii);
  EXPECT_EQ(a, b);
  ASSERT_EQ(a.size(), c.size());
  EXPECT_NE(a[0].transform, c[0].transform);
}

TEST(RandomPlacement, KeepsEntryOrderAndExplicitTransforms) {
  const SceneDescription s = mixed_scene(3);
  const auto placed = expand_random_instances(s, radii);
  ASSERT_EQ(placed.size(), 46u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(placed[i].compartment, big);
  EXPECT_EQ(placed[5].compartment, big);
  EXPECT_EQ(placed[5].transform, std::get<ExplicitInstance>(s.instances[1]).transform);
  for (std::size_t i = 6; i < 46; ++i) EXPECT_EQ(placed[i].compartment, small);
}

TEST(RandomPlacement, NoOverlapAllInsideRigidRotations) {
  const auto placed = expand_random_instances(mixed_scene(5), radii);
  constexpr std::size_t explicit_index = 5;
  auto radius_of = [&](std::size_t i) { return i == explicit_index ? 600.0 : radii[placed[i].compartment.index]; };
  for (std::size_t i = 0; i < placed.size(); ++i) {
    const glm::dvec3 ci = centre_of(placed[i].transform);
    // Brute force over all pairs; every pair involves a random copy with the same min_gap.
    for (std::size_t j = i + 1; j < placed.size(); ++j)
      EXPECT_GE(glm::distance(ci, centre_of(placed[j].transform)), radius_of(i) + radius_of(j) + gap)
          << "instances " << i << " and " << j;
    if (i == explicit_index) continue;
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_GE(ci[axis] - radius_of(i), box.min[axis]) << "instance " << i;
      EXPECT_LE(ci[axis] + radius_of(i), box.max[axis]) << "instance " << i;
    }
    // Rotation rows are orthonormal with determinant +1: no scale, shear or mirror sneaks in.
    const auto& m = placed[i].transform;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(glm::dot(glm::dvec3(m[r]), glm::dvec3(m[c])), r == c ? 1.0 : 0.0, 1e-12);
    EXPECT_NEAR(linear_determinant(m), 1.0, 1e-12);
  }
}

TEST(RandomPlacement, ThousandsOfCopiesBesideALargeExplicitOneNeverOverlap) {
  // The grid that finds neighbours must answer what testing every pair answers: checked here pair
  // by pair, with a scaled-up explicit copy wider than a grid cell in the middle of the box.
  const Box wide{{-6000, -6000, -6000}, {6000, 6000, 6000}};
  const SceneDescription s = scene_with({ExplicitInstance{big, translate_rotate_scale({0, 0, 0}, {0, 0, 1}, 0, 8.0)},
                                         RandomPlacement{small, 3000, wide, 9, 20.0}, RandomPlacement{big, 40, wide, 4, 0.0}});
  const auto placed = expand_random_instances(s, radii);
  ASSERT_EQ(placed.size(), 3041u);
  const auto radius = [&](std::size_t i) { return i == 0 ? 8.0 * radii[0] : radii[placed[i].compartment.index]; };
  for (std::size_t i = 0; i < placed.size(); ++i)
    for (std::size_t j = i + 1; j < placed.size(); ++j) {
      const double gap_needed = j <= 3000 ? 20.0 : 0.0;  // the min_gap of the entry placed later
      ASSERT_GE(glm::distance(centre_of(placed[i].transform), centre_of(placed[j].transform)),
                radius(i) + radius(j) + gap_needed - 1e-9)
          << i << " " << j;
    }
}

TEST(RandomPlacement, CopiesOfVeryDifferentSizesNeverOverlap) {
  // A cell-sized copy placed at random among thousands of virion-sized ones: each size has its own
  // grid, and every pair is still checked here one by one.
  const std::vector<double> mixed = {20000.0, 100.0};
  const Box wide{{-40000, -40000, -40000}, {40000, 40000, 40000}};
  const SceneDescription s =
      scene_with({RandomPlacement{big, 2, wide, 3, 0.0}, RandomPlacement{small, 3000, wide, 5, 50.0}});
  const auto placed = expand_random_instances(s, mixed);
  ASSERT_EQ(placed.size(), 3002u);
  for (std::size_t i = 0; i < placed.size(); ++i)
    for (std::size_t j = i + 1; j < placed.size(); ++j)
      ASSERT_GE(glm::distance(centre_of(placed[i].transform), centre_of(placed[j].transform)),
                mixed[placed[i].compartment.index] + mixed[placed[j].compartment.index] + (j >= 2 ? 50.0 : 0.0) - 1e-9)
          << i << " " << j;
}

TEST(RandomPlacement, RotationsCoverTheSphereEvenly) {
  // For uniformly random rotations the image of any fixed axis is uniform on the sphere, so each
  // component has mean 0 and mean square 1/3. 4000 samples: standard error ≈ 0.009 for the mean.
  const auto placed = expand_random_instances(
      scene_with({RandomPlacement{small, 4000, {{-1e7, -1e7, -1e7}, {1e7, 1e7, 1e7}}, 77, 0.0}}), radii);
  glm::dvec3 mean(0.0), mean_square(0.0);
  for (const auto& p : placed) {
    const glm::dvec3 z_image(p.transform[0][2], p.transform[1][2], p.transform[2][2]);
    mean += z_image / 4000.0;
    mean_square += z_image * z_image / 4000.0;
  }
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(mean[axis], 0.0, 0.05);
    EXPECT_NEAR(mean_square[axis], 1.0 / 3.0, 0.03);
  }
}

TEST(RandomPlacement, ImpossiblePackingNamesTheEntry) {
  // Centres must lie in [100, 100] × [100, 100] × [100, 290]: two spheres of radius 100 are at
  // most 190 apart there, so the second never fits.
  const SceneDescription s = scene_with({ExplicitInstance{big, translate_rotate_scale({5e4, 0, 0}, {0, 0, 1}, 0, 1)},
                                         RandomPlacement{small, 2, {{0, 0, 0}, {200, 200, 390}}, 1, 0.0}});
  EXPECT_INPUT_ERROR(expand_random_instances(s, radii), "instances[1]", "placed only 1 of 2 copies of compartment \"small\"");
}

TEST(RandomPlacement, SphereLargerThanTheBox) {
  const SceneDescription s = scene_with({RandomPlacement{big, 1, {{0, 0, 0}, {500, 5000, 5000}}, 1, 0.0}});
  EXPECT_INPUT_ERROR(expand_random_instances(s, radii), "instances[0]", "does not fit inside the box");
}

TEST(RandomPlacement, ExplicitInstanceBlocksTheOnlyRoom) {
  // The box has room for exactly one radius-100 sphere centred at (100, 100, 100); an explicit
  // instance sits there (its scale 0.5 shrinks radius 300 to 150), so nothing can be placed.
  const SceneDescription s = scene_with({RandomPlacement{small, 1, {{0, 0, 0}, {200, 200, 200}}, 1, 0.0},
                                         ExplicitInstance{big, translate_rotate_scale({100, 100, 100}, {1, 0, 0}, 30, 0.5)}});
  EXPECT_INPUT_ERROR(expand_random_instances(s, radii), "instances[0]", "placed only 0 of 1");
}

TEST(RandomPlacement, RadiiMustMatchTheCompartments) {
  EXPECT_THROW(expand_random_instances(mixed_scene(1), {300.0}), std::invalid_argument);
  EXPECT_THROW(expand_random_instances(mixed_scene(1), {300.0, 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace nano::scene
