#include "bake/grid/mesh_surface.hpp"

#include <random>

#include <gtest/gtest.h>

#include "bake/mesh/rbc_mesh.hpp"
#include "bake/mesh/sphere_mesh.hpp"
#include "common/error.hpp"
#include "tests/grid/grid_oracles.hpp"

namespace nano::grid {
namespace {

TEST(MeshSurface, ContainsAndDistanceMatchOracles) {
  const mesh::ProxyMesh m = mesh::make_rbc_mesh(600);  // non-convex
  const MeshSurface s(m);
  EXPECT_EQ(s.mesh().triangles, m.triangles);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-42000.0, 42000.0), uz(-15000.0, 15000.0);
  int inside = 0;
  for (int n = 0; n < 400; ++n) {
    const glm::dvec3 p(u(rng), u(rng), uz(rng));
    const double d = oracle::mesh_distance(m, p);
    EXPECT_NEAR(std::sqrt(s.squared_distance(p)), d, 1e-6 * (1.0 + d));
    if (d > 1.0) {
      EXPECT_EQ(s.contains(p), oracle::mesh_contains(m, p)) << p.x << " " << p.y << " " << p.z;
      inside += s.contains(p);
    }
  }
  EXPECT_GT(inside, 20);
  EXPECT_FALSE(s.contains({0.0, 0.0, 8000.0}));  // the dimple above the centre
  EXPECT_TRUE(s.contains({0.0, 0.0, 0.0}));
  EXPECT_FALSE(s.contains(m.positions[0]));       // on the surface: not strictly inside
}

TEST(MeshSurface, TrianglesMeetingBoxAgainstBruteForce) {
  const mesh::ProxyMesh m = mesh::make_sphere_mesh(300, 1000.0);
  const MeshSurface s(m);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1100.0, 1100.0);
  const double half = 100.0;
  for (int n = 0; n < 200; ++n) {
    const glm::dvec3 c(u(rng), u(rng), u(rng));
    const std::vector<std::uint32_t> got = s.triangles_meeting(c - half, c + half);
    EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
    for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
      const auto& tri = m.triangles[t];
      const double d = oracle::triangle_distance(c, m.positions[tri[0]], m.positions[tri[1]], m.positions[tri[2]]);
      const bool listed = std::binary_search(got.begin(), got.end(), t);
      if (d <= half * 0.999) {
        EXPECT_TRUE(listed) << t;  // meets the inscribed ball
      }
      if (d > half * std::sqrt(3.0) * 1.001) {
        EXPECT_FALSE(listed) << t;  // misses the circumscribed ball
      }
    }
  }
}

TEST(MeshSurface, BadMeshesThrow) {
  EXPECT_THROW(MeshSurface(mesh::ProxyMesh{}), InputError);
  mesh::ProxyMesh open = mesh::make_sphere_mesh(48, 10.0);
  open.triangles.pop_back();
  EXPECT_THROW(MeshSurface{open}, InputError);
  mesh::ProxyMesh out_of_range = mesh::make_sphere_mesh(48, 10.0);
  out_of_range.triangles[0][1] = 100000;
  EXPECT_THROW(MeshSurface{out_of_range}, InputError);
  mesh::ProxyMesh non_manifold = mesh::make_sphere_mesh(48, 10.0);
  non_manifold.triangles.push_back(non_manifold.triangles[0]);
  EXPECT_THROW(MeshSurface{non_manifold}, InputError);
}

}  // namespace
}  // namespace nano::grid
