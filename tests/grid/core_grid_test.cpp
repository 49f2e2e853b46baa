#include "bake/grid/core_grid.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "bake/mesh/sphere_mesh.hpp"
#include "common/error.hpp"

namespace nano::grid {
namespace {

// A closed tetrahedron spanning [0, 10] × [0, 4] × [−1, 1] (only its AABB matters here).
mesh::ProxyMesh tetrahedron() {
  mesh::ProxyMesh m;
  m.positions = {{0, 0, -1}, {10, 0, -1}, {0, 4, -1}, {0, 0, 1}};
  m.triangles = {{{0, 2, 1}}, {{0, 1, 3}}, {{0, 3, 2}}, {{1, 2, 3}}};
  return m;
}

TEST(CoreGrid, StrictlyContainsAndCentresOnTheMeshAabb) {
  // Extents 10, 4, 2 with S = 2: floor(extent/S) + 1 = 6, 3, 2 boxes; margins 1, 1, 1.
  const CoreGrid g = make_core_grid(tetrahedron(), 2.0);
  EXPECT_EQ(g.dims, glm::ivec3(6, 3, 2));
  EXPECT_EQ(g.min, glm::dvec3(-1.0, -1.0, -2.0));
  EXPECT_EQ(g.max(), glm::dvec3(11.0, 5.0, 2.0));
  EXPECT_EQ(g.box_count(), 36u);
  // S = 3: 4, 2, 1 boxes (extents 12, 6, 3 → margins 1, 1, 0.5).
  const CoreGrid h = make_core_grid(tetrahedron(), 3.0);
  EXPECT_EQ(h.dims, glm::ivec3(4, 2, 1));
  EXPECT_EQ(h.min, glm::dvec3(-1.0, -1.0, -1.5));
}

TEST(CoreGrid, BoxOfIsFloorAndHalfOpen) {
  CoreGrid g;
  g.min = {-1.0, -1.0, -2.0};
  g.box_size = 2.0;
  g.dims = {6, 3, 2};
  EXPECT_EQ(g.box_of({0.0, 0.0, 0.0}), glm::ivec3(0, 0, 1));
  EXPECT_EQ(g.box_of({1.0, 1.0, 0.0}), glm::ivec3(1, 1, 1));       // on the faces x = 1, y = 1: box above
  EXPECT_EQ(g.box_of({0.999, 0.999, -0.001}), glm::ivec3(0, 0, 0));
  EXPECT_EQ(g.box_of({-1.0, -1.0, -2.0}), glm::ivec3(0, 0, 0));    // grid minimum corner
  EXPECT_EQ(g.box_of({11.0, 5.0, 2.0}), glm::ivec3(6, 3, 2));      // grid maximum: outside (half-open)
  EXPECT_EQ(g.box_of({-1.5, 0.0, 0.0}), glm::ivec3(-1, 0, 1));     // floor, not truncation
  EXPECT_TRUE(g.contains({5, 2, 1}));
  EXPECT_FALSE(g.contains({6, 0, 0}));
  EXPECT_FALSE(g.contains({0, -1, 0}));
  EXPECT_FALSE(g.contains({0, 0, 2}));
  EXPECT_EQ(g.box_min({2, 1, 1}), glm::dvec3(3.0, 1.0, 0.0));
  EXPECT_EQ(g.box_centre({2, 1, 1}), glm::dvec3(4.0, 2.0, 1.0));
  EXPECT_EQ(g.linear_index({2, 1, 1}), 2u + 6u * (1u + 3u * 1u));
  EXPECT_EQ(g.box_at(26u), glm::ivec3(2, 1, 1));
  for (BoxIndex i = 0; i < g.box_count(); ++i) EXPECT_EQ(g.linear_index(g.box_at(i)), i);
}

TEST(CoreGrid, BadInputThrows) {
  EXPECT_THROW(make_core_grid(mesh::ProxyMesh{}, 1.0), InputError);
  EXPECT_THROW(make_core_grid(tetrahedron(), 0.0), InputError);
  EXPECT_THROW(make_core_grid(tetrahedron(), -2.0), InputError);
  EXPECT_THROW(make_core_grid(tetrahedron(), std::nan("")), InputError);
  EXPECT_THROW(make_core_grid(tetrahedron(), 1e-4), InputError);  // 1e5·4e4·2e4 boxes > 2^31
  EXPECT_THROW(make_core_grid(tetrahedron(), 1.0, GridLimits{100}), InputError);  // 11·5·3 = 165 > 100
  EXPECT_NO_THROW(make_core_grid(tetrahedron(), 1.0, GridLimits{165}));
  mesh::ProxyMesh bad = tetrahedron();
  bad.positions[3].z = std::numeric_limits<double>::infinity();
  EXPECT_THROW(make_core_grid(bad, 1.0), InputError);
  bad = tetrahedron();
  bad.triangles[0][0] = 9;
  EXPECT_THROW(make_core_grid(bad, 1.0), InputError);
}

TEST(CoreGrid, SphereGridIsSymmetric) {
  const mesh::ProxyMesh m = mesh::make_sphere_mesh(300, 1000.0);
  const CoreGrid g = make_core_grid(m, 300.0);
  EXPECT_EQ(g.dims, glm::ivec3(7, 7, 7));  // floor(2000 / 300) + 1
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(g.min[a] + g.max()[a], 0.0, 1e-9);
}

}  // namespace
}  // namespace nano::grid
