#include "bake/grid/triangle_distance.hpp"

#include <random>

#include <gtest/gtest.h>

#include "tests/grid/grid_oracles.hpp"

namespace nano::grid {
namespace {

TEST(TriangleDistance, HandCases) {
  const glm::dvec3 a(0, 0, 0), b(4, 0, 0), c(0, 4, 0);
  EXPECT_EQ(closest_point_on_triangle({1, 1, 3}, a, b, c), glm::dvec3(1, 1, 0));   // face
  EXPECT_EQ(closest_point_on_triangle({-2, -3, 0}, a, b, c), a);                   // vertex
  EXPECT_EQ(closest_point_on_triangle({2, -5, 1}, a, b, c), glm::dvec3(2, 0, 0));  // edge ab
  EXPECT_EQ(closest_point_on_triangle({3, 3, 0}, a, b, c), glm::dvec3(2, 2, 0));   // edge bc
  EXPECT_DOUBLE_EQ(squared_distance_to_triangle({1, 1, 3}, a, b, c), 9.0);
  EXPECT_DOUBLE_EQ(squared_distance_to_triangle({3, 3, 0}, a, b, c), 2.0);
}

TEST(TriangleDistance, MatchesIndependentOracle) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  for (int n = 0; n < 20000; ++n) {
    const glm::dvec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng)), p(u(rng), u(rng), u(rng));
    const double expected = oracle::triangle_distance(p, a, b, c);
    EXPECT_NEAR(std::sqrt(squared_distance_to_triangle(p, a, b, c)), expected, 1e-9 * (1.0 + expected));
  }
}

}  // namespace
}  // namespace nano::grid
