#include "bake/tiles/rotation_sampling.hpp"
#include "bake/tiles/tile_random.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace nano::tiles {
namespace {

TEST(TileRandom, SameSeedSameStreamAndUniformInRange) {
  SplitMix64 a(42), b(42), c(43);
  int differ = 0;
  std::array<int, 10> bins{};
  for (int i = 0; i < 10000; ++i) {
    const uint64_t x = a.next();
    EXPECT_EQ(x, b.next());
    differ += x != c.next();
    const double u = a.uniform();
    b.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    ++bins[static_cast<int>(u * 10)];
    c.uniform();
  }
  EXPECT_GT(differ, 9990);
  for (int n : bins) EXPECT_NEAR(n, 1000, 150);  // > 4 sigma
  SplitMix64 d(7);
  std::array<int, 3> below{};
  for (int i = 0; i < 3000; ++i) ++below[d.below(3)];
  for (int n : below) EXPECT_NEAR(n, 1000, 120);
}

TEST(TileRandom, LatticeHashDependsOnEveryArgument) {
  std::set<uint64_t> seen;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j)
      for (int k = -2; k <= 2; ++k)
        for (uint32_t tag = 0; tag < 3; ++tag) seen.insert(lattice_hash(5, i, j, k, tag));
  EXPECT_EQ(seen.size(), 5u * 5 * 5 * 3);
  EXPECT_NE(lattice_hash(5, 1, 2, 3, 0), lattice_hash(6, 1, 2, 3, 0));
  EXPECT_EQ(lattice_hash(5, 1, 2, 3, 0), lattice_hash(5, 1, 2, 3, 0));
  EXPECT_NE(mix64(1), mix64(2));
}

// Uniform on SO(3): the image of a fixed vector is uniform on the sphere, so every component has
// mean 0 and mean square 1/3, and the quaternions have unit norm.
TEST(RotationSampling, UniformRotationsSpreadVectorsUniformly) {
  SplitMix64 rng(3);
  glm::dvec3 mean(0.0), square(0.0);
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const glm::quat q = uniform_rotation(rng);
    ASSERT_NEAR(glm::length(q), 1.f, 1e-5f);
    const glm::dvec3 v = glm::dvec3(glm::mat3_cast(q) * glm::vec3(0.3f, -0.5f, 0.812404f));
    mean += v;
    square += v * v;
  }
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(mean[a] / n, 0.0, 0.02);
    EXPECT_NEAR(square[a] / n, 1.0 / 3.0, 0.02);
  }
}

TEST(RotationSampling, RotationBetweenMapsFromOntoTo) {
  SplitMix64 rng(9);
  for (int i = 0; i < 200; ++i) {
    const glm::vec3 from = glm::normalize(glm::vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)));
    const glm::vec3 to = glm::normalize(glm::vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)));
    for (const glm::vec3 target : {to, -from, from}) {
      const glm::vec3 got = glm::mat3_cast(rotation_between(from, target)) * from;
      EXPECT_NEAR(glm::length(got - target), 0.f, 1e-4f);
    }
  }
}

TEST(RotationSampling, SpinAboutZKeepsZAndTurnsX) {
  const glm::mat3 r = glm::mat3_cast(spin_about_z(M_PI / 2));
  EXPECT_NEAR(glm::length(r * glm::vec3(0, 0, 1) - glm::vec3(0, 0, 1)), 0.f, 1e-6f);
  EXPECT_NEAR(glm::length(r * glm::vec3(1, 0, 0) - glm::vec3(0, 1, 0)), 0.f, 1e-6f);
}

}  // namespace
}  // namespace nano::tiles
