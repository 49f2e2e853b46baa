// The UV→world Jacobian and what is derived from it, against hand-computed values.
#include <cmath>

#include <gtest/gtest.h>

#include "bake/mesh/uv_distortion.hpp"

namespace nano::mesh {
namespace {

// One triangle: world corners scaled by 2 in x and 3 in y from its UV right triangle.
ProxyMesh scaled_right_triangle() {
  ProxyMesh mesh;
  mesh.positions = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}};
  mesh.triangles = {{0, 1, 2}};
  mesh.uvs = {{0, 0}, {1, 0}, {0, 1}};
  mesh.uv_triangles = {{0, 1, 2}};
  return mesh;
}

TEST(UvJacobian, ScaledRightTriangleHasColumnsOfTheScale) {
  const auto j = uv_jacobian(scaled_right_triangle(), 0);
  ASSERT_TRUE(j);
  EXPECT_EQ(j->du, glm::dvec3(2, 0, 0));
  EXPECT_EQ(j->dv, glm::dvec3(0, 3, 0));
  const SingularValues sv = singular_values(*j);
  EXPECT_DOUBLE_EQ(sv.major, 3.0);
  EXPECT_DOUBLE_EQ(sv.minor, 2.0);
}

TEST(UvJacobian, IndependentOfCornerOrderAndPlacement) {
  // Same affine map X = A·uv + b with A = [[2,0],[0,3],[0,0]] rotated by 30° about z and moved;
  // UV corners chosen arbitrarily: J must be the rotated A whatever the corners are.
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  auto map = [&](glm::dvec2 t) { return glm::dvec3(c * 2 * t.x - s * 3 * t.y + 5, s * 2 * t.x + c * 3 * t.y - 1, 7); };
  const std::array<glm::dvec2, 3> uv = {glm::dvec2(0.3, 0.1), glm::dvec2(0.35, 0.4), glm::dvec2(0.1, 0.2)};
  const auto j = uv_jacobian({map(uv[0]), map(uv[1]), map(uv[2])}, uv);
  ASSERT_TRUE(j);
  EXPECT_NEAR(j->du.x, 2 * c, 1e-12);
  EXPECT_NEAR(j->du.y, 2 * s, 1e-12);
  EXPECT_NEAR(j->dv.x, -3 * s, 1e-12);
  EXPECT_NEAR(j->dv.y, 3 * c, 1e-12);
  const SingularValues sv = singular_values(*j);
  EXPECT_NEAR(sv.major, 3.0, 1e-12);
  EXPECT_NEAR(sv.minor, 2.0, 1e-12);
}

TEST(UvJacobian, ShearHasTheAnalyticSingularValues) {
  // J = [[1, 1], [0, 1], [0, 0]]: σ² are the eigenvalues of [[1,1],[1,2]] = (3 ± √5) / 2.
  const SingularValues sv = singular_values({{1, 0, 0}, {1, 1, 0}});
  EXPECT_NEAR(sv.major, std::sqrt((3 + std::sqrt(5.0)) / 2), 1e-14);
  EXPECT_NEAR(sv.minor, std::sqrt((3 - std::sqrt(5.0)) / 2), 1e-14);
}

TEST(UvJacobian, ZeroAreaUvTriangleHasNone) {
  EXPECT_FALSE(uv_jacobian({glm::dvec3(0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)},
                           {glm::dvec2(0), glm::dvec2(0.5, 0.5), glm::dvec2(1, 1)}));
}

TEST(UvScale, IsSquareRootOfAreaRatio) {
  const ProxyMesh mesh = scaled_right_triangle();
  EXPECT_DOUBLE_EQ(world_area(mesh, 0), 3.0);
  EXPECT_DOUBLE_EQ(uv_signed_area(mesh, 0), 0.5);
  EXPECT_DOUBLE_EQ(uv_scale(mesh), std::sqrt(6.0));
  // Normalised by k the singular values are 3/√6 and 2/√6: their product (area ratio) is 1.
  EXPECT_NEAR(3 / uv_scale(mesh) * 2 / uv_scale(mesh), 1.0, 1e-15);
}

TEST(UvScale, MirroredUvTriangleCountsItsArea) {
  ProxyMesh mesh = scaled_right_triangle();
  mesh.uv_triangles = {{0, 2, 1}};
  EXPECT_DOUBLE_EQ(uv_signed_area(mesh, 0), -0.5);
  EXPECT_DOUBLE_EQ(uv_scale(mesh), std::sqrt(6.0));
}

// scaled_right_triangle plus a second triangle stretched by 0.5 and 4 (shear-free).
ProxyMesh two_stretched_triangles() {
  ProxyMesh mesh = scaled_right_triangle();
  mesh.positions.push_back({10, 0, 0});
  mesh.positions.push_back({10.5, 0, 0});
  mesh.positions.push_back({10, 4, 0});
  mesh.triangles.push_back({3, 4, 5});
  mesh.uv_triangles.push_back({0, 1, 2});
  return mesh;
}

TEST(SmallestStretch, IsTheLeastSingularValueOverTriangles) {
  EXPECT_DOUBLE_EQ(smallest_stretch(scaled_right_triangle()), 2.0);  // σ = 3, 2
  // The second triangle's σ2 = 0.5 becomes the smallest.
  ProxyMesh mesh = two_stretched_triangles();
  EXPECT_DOUBLE_EQ(smallest_stretch(mesh), 0.5);
  // A zero-area UV triangle has no chart and is ignored.
  mesh.uvs.push_back({0.5, 0.5});
  mesh.positions.push_back({20, 0, 0});
  mesh.triangles.push_back({0, 1, 6});
  mesh.uv_triangles.push_back({3, 3, 3});
  EXPECT_DOUBLE_EQ(smallest_stretch(mesh), 0.5);
}

TEST(ChartAnisotropy, IsLargestOverSmallestStretchAcrossTriangles) {
  EXPECT_DOUBLE_EQ(chart_anisotropy(scaled_right_triangle()), 1.5);  // σ = 3, 2
  // With the second triangle (σ = 4 and 0.5) the range becomes [0.5, 4] though no single triangle
  // spans it; the bound must cover a copy pair straddling both.
  EXPECT_DOUBLE_EQ(chart_anisotropy(two_stretched_triangles()), 8.0);
  ProxyMesh flat = scaled_right_triangle();
  flat.uvs = {{0, 0}, {0, 0}, {0, 0}};
  EXPECT_EQ(chart_anisotropy(flat), 0.0);
}

TEST(ReplicationArea, CeilOfExtentOverTileSizePlusOne) {
  EXPECT_EQ(tiles_spanning(0.25, 0.1), 4);  // ceil(2.5) + 1
  EXPECT_EQ(tiles_spanning(0.05, 0.1), 2);
  EXPECT_EQ(tiles_spanning(0.0, 0.1), 1);
  ProxyMesh mesh = scaled_right_triangle();
  // Binary fractions, so that extent / s is exact and ceil sees no rounding.
  mesh.uvs = {{0.125, 0.125}, {0.4375, 0.125}, {0.125, 0.1875}, {0.5, 0.5}, {0.5625, 0.5}, {0.5, 0.875}};
  mesh.positions.push_back({0, 0, 1});
  mesh.positions.push_back({1, 0, 1});
  mesh.positions.push_back({0, 1, 1});
  mesh.triangles.push_back({3, 4, 5});
  mesh.uv_triangles.push_back({3, 4, 5});
  EXPECT_EQ(triangle_tile_span(mesh, 0, 0.125), (std::array<int, 2>{4, 2}));  // 2.5 → 3 + 1, 0.5 → 1 + 1
  EXPECT_EQ(triangle_tile_span(mesh, 1, 0.125), (std::array<int, 2>{2, 4}));  // exactly 3 tiles → 3 + 1
  EXPECT_EQ(replication_area(mesh, 0.125), (std::array<int, 2>{4, 4}));
}

}  // namespace
}  // namespace nano::mesh
