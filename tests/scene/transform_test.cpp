#include "bake/scene/transform.hpp"
#include "bake/scene/transform_parser.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

namespace nano::scene {
namespace {

void expect_matrix_near(const Matrix3x4& actual, const Matrix3x4& expected, double tolerance = 1e-12) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(actual[r][c], expected[r][c], tolerance) << "row " << r << " col " << c;
}

TEST(Transform, Identity) {
  const Matrix3x4 expected = {glm::dvec4(1, 0, 0, 0), glm::dvec4(0, 1, 0, 0), glm::dvec4(0, 0, 1, 0)};
  EXPECT_EQ(identity_transform(), expected);
}

TEST(Transform, QuarterTurnAboutZWithScaleAndTranslation) {
  // x -> 2y, y -> -2x, then + (10, 20, 30).
  expect_matrix_near(translate_rotate_scale({10, 20, 30}, {0, 0, 5}, 90, 2),
                     {glm::dvec4(0, -2, 0, 10), glm::dvec4(2, 0, 0, 20), glm::dvec4(0, 0, 2, 30)});
}

TEST(Transform, ThirdOfATurnAboutTheDiagonalCyclesTheAxes) {
  // 120° about (1,1,1) maps x -> y -> z -> x.
  expect_matrix_near(translate_rotate_scale({0, 0, 0}, {1, 1, 1}, 120, 1),
                     {glm::dvec4(0, 0, 1, 0), glm::dvec4(1, 0, 0, 0), glm::dvec4(0, 1, 0, 0)});
}

TEST(Transform, NegativeAngleTurnsClockwise) {
  expect_matrix_near(translate_rotate_scale({0, 0, 0}, {1, 0, 0}, -90, 1),
                     {glm::dvec4(1, 0, 0, 0), glm::dvec4(0, 0, 1, 0), glm::dvec4(0, -1, 0, 0)});
}

TEST(Transform, RigidFromQuaternion) {
  // q = (cos 45°, 0, 0, sin 45°) is 90° about z.
  const double h = std::sqrt(0.5);
  expect_matrix_near(rigid_transform({h, 0, 0, h}, {1, 2, 3}),
                     {glm::dvec4(0, -1, 0, 1), glm::dvec4(1, 0, 0, 2), glm::dvec4(0, 0, 1, 3)});
  // q = (0, 1, 0, 0) is 180° about x.
  expect_matrix_near(rigid_transform({0, 1, 0, 0}, {0, 0, 0}),
                     {glm::dvec4(1, 0, 0, 0), glm::dvec4(0, -1, 0, 0), glm::dvec4(0, 0, -1, 0)});
}

TEST(Transform, TransformPoint) {
  const Matrix3x4 m = {glm::dvec4(0, -2, 0, 10), glm::dvec4(2, 0, 0, 20), glm::dvec4(0, 0, 2, 30)};
  EXPECT_EQ(transform_point(m, {1, 1, 1}), glm::dvec3(8, 22, 32));
}

TEST(Transform, Determinant) {
  EXPECT_EQ(linear_determinant(identity_transform()), 1.0);
  const Matrix3x4 m = {glm::dvec4(2, 1, 0, 9), glm::dvec4(0, 3, 0, 9), glm::dvec4(0, 0, -1, 9)};
  EXPECT_EQ(linear_determinant(m), -6.0);
}

TEST(Transform, LargestStretchOfDiagonalRotatedAndShearedMatrices) {
  const Matrix3x4 diagonal = {glm::dvec4(1, 0, 0, 5), glm::dvec4(0, -3, 0, 5), glm::dvec4(0, 0, 2, 5)};
  EXPECT_NEAR(largest_stretch(diagonal), 3.0, 1e-12);
  EXPECT_NEAR(largest_stretch(translate_rotate_scale({1, 2, 3}, {1, 2, 3}, 37, 4.5)), 4.5, 1e-12);
  // The shear [[1, 1], [0, 1]] has singular values φ and 1/φ (φ the golden ratio).
  const Matrix3x4 shear = {glm::dvec4(1, 1, 0, 0), glm::dvec4(0, 1, 0, 0), glm::dvec4(0, 0, 1, 0)};
  EXPECT_NEAR(largest_stretch(shear), (1.0 + std::sqrt(5.0)) / 2.0, 1e-12);
}

TEST(Transform, RescaledByPowerOfTwoIsExactAndBringsTheLargestComponentIntoOneToTwo) {
  // Exact: only the exponent moves, so the components keep their ratios bit for bit.
  EXPECT_EQ(rescaled_by_power_of_two({3.0, -0.75, 0.0}), glm::dvec3(1.5, -0.375, 0.0));
  EXPECT_EQ(rescaled_by_power_of_two({1.0, 1.0, 1.0}), glm::dvec3(1.0, 1.0, 1.0));
  // Components that would under- or overflow when squared for a length come back into range.
  const glm::dvec3 tiny = rescaled_by_power_of_two({1e-200, 0.0, 0.0});
  EXPECT_GE(tiny.x, 1.0);
  EXPECT_LT(tiny.x, 2.0);
  const glm::dvec3 huge = rescaled_by_power_of_two({1e300, -1e300, 0.0});
  EXPECT_TRUE(std::isfinite(glm::dot(huge, huge)));
  EXPECT_EQ(huge.x, -huge.y);
  EXPECT_GE(std::abs(huge.x), 1.0);
  EXPECT_LT(std::abs(huge.x), 2.0);
}

}  // namespace
}  // namespace nano::scene
