// Will a bilayer fit (bake/mesh/membrane_fit.hpp): walls, gaps and creases against analytic sizes.
#include "bake/mesh/membrane_fit.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "bake/mesh/sphere_mesh.hpp"

namespace nano::mesh {
namespace {

// Boxes [lo, lo + size] as 12 outward triangles each, appended to one mesh.
void add_box(ProxyMesh& m, const glm::dvec3& lo, const glm::dvec3& size) {
  const std::uint32_t first = static_cast<std::uint32_t>(m.positions.size());
  for (int i = 0; i < 8; ++i) m.positions.push_back(lo + size * glm::dvec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({first + q[0], first + q[1], first + q[2]});
    m.triangles.push_back({first + q[0], first + q[2], first + q[3]});
  }
}

MembraneFit judge(ProxyMesh m, double thickness) {
  MeshReport report = check_mesh(m, {});
  return fit_membrane(m, report, thickness, RemeshPolicy{});
}

TEST(MembraneFit, ABoxWithWallsOfFiveBilayersFitsAndIsRemeshed) {
  ProxyMesh m;
  add_box(m, glm::dvec3(0.0), glm::dvec3(kCreaseWallAt90 * 40.0 + 1.0));
  const MembraneFit fit = judge(m, 40.0);
  EXPECT_TRUE(fit.fits());
  EXPECT_TRUE(fit.remesh.has_value()) << "90° creases are remeshed";
  EXPECT_NEAR(fit.thinnest_wall, kCreaseWallAt90 * 40.0 + 1.0, 1e-9);
  EXPECT_EQ(fit.narrowest_gap, INFINITY);
}

TEST(MembraneFit, ASmallBoxCannotRoundItsCreasesAndSaysAtWhatSize) {
  ProxyMesh m;
  add_box(m, glm::dvec3(0.0), glm::dvec3(150.0));
  const MembraneFit fit = judge(m, 40.0);
  ASSERT_FALSE(fit.fits());
  EXPECT_FALSE(fit.remesh.has_value()) << "judged before remeshing";
  EXPECT_EQ(fit.tight.front().what, "crease");
  EXPECT_NEAR(fit.tight.front().found, 150.0, 1e-9);
  EXPECT_NEAR(fit.tight.front().needed, kCreaseWallAt90 * 40.0, 1e-6);
  EXPECT_NEAR(fit.scale_needed, kCreaseWallAt90 * 40.0 / 150.0, 1e-6);
  const std::string text = describe_tight_features(fit, 40.0, 900.0);
  EXPECT_NE(text.find("a 90° crease on a wall 150.0 Å thick"), std::string::npos) << text;
  EXPECT_NE(text.find("\"diameter\": 1200 Å or more"), std::string::npos) << text;
  EXPECT_NE(describe_tight_features(fit, 40.0, std::nullopt).find("scaled by 1.33"), std::string::npos);
}

TEST(MembraneFit, AWallThinnerThanTheBilayerIsNamedWithItsLocalRadius) {
  // A fine sphere of radius 15 Å: every wall is a diameter, 30 Å, under a 40 Å bilayer.
  const MembraneFit fit = judge(make_sphere_mesh(2000, 15.0), 40.0);
  ASSERT_FALSE(fit.fits());
  EXPECT_EQ(fit.tight.front().what, "wall");
  EXPECT_NEAR(fit.tight.front().found, 30.0, 0.5);
  EXPECT_NEAR(fit.scale_needed, 40.0 / 30.0, 0.03);
  EXPECT_NE(describe_tight_features(fit, 40.0, 30.0).find("local radius 1"), std::string::npos);
}

TEST(MembraneFit, AGapNarrowerThanTheBilayerIsNamed) {
  // Two smooth spheres 20 Å apart, each large enough to hold the bilayer.
  ProxyMesh m = make_sphere_mesh(4000, 300.0);
  const ProxyMesh other = make_sphere_mesh(4000, 300.0);
  const std::uint32_t first = static_cast<std::uint32_t>(m.positions.size());
  for (const glm::dvec3& p : other.positions) m.positions.push_back(p + glm::dvec3(620.0, 0.0, 0.0));
  for (const Triangle& t : other.triangles) m.triangles.push_back({first + t[0], first + t[1], first + t[2]});
  m.uvs.clear(), m.uv_triangles.clear(), m.normals.clear(), m.normal_triangles.clear();  // the corners of one sphere only
  const MembraneFit fit = judge(m, 40.0);
  ASSERT_FALSE(fit.fits());
  EXPECT_EQ(fit.tight.front().what, "gap");
  EXPECT_NEAR(fit.narrowest_gap, 20.0, 3.0);  // from facet centroids, which sag inside the spheres
  EXPECT_GT(fit.thinnest_wall, 590.0);
}

TEST(MembraneFit, RemeshOffJudgesWallsButNotCreases) {
  ProxyMesh m;
  add_box(m, glm::dvec3(0.0), glm::dvec3(150.0));
  MeshReport report = check_mesh(m, {});
  RemeshPolicy off;
  off.mode = RemeshPolicy::Mode::off;
  const MembraneFit fit = fit_membrane(m, report, 40.0, off);
  EXPECT_TRUE(fit.fits()) << "the scene keeps its mesh: the shells judge it";
  EXPECT_FALSE(fit.remesh.has_value());
}

}  // namespace
}  // namespace nano::mesh
