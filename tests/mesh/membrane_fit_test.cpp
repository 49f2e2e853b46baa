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
  return fit_membrane(m, report, thickness, RemeshPolicy{}, "m.obj");
}

TEST(MembraneFit, ABoxOfTenBilayersFitsAndIsRemeshed) {
  ProxyMesh m;
  const double side = 10.0 * 40.0;
  add_box(m, glm::dvec3(0.0), glm::dvec3(side));
  const MembraneFit fit = judge(m, 40.0);
  EXPECT_TRUE(fit.fits());
  ASSERT_TRUE(fit.remesh.has_value()) << "90° creases are remeshed";
  EXPECT_LE(fit.remesh->largest_crease_out, kRemeshCreaseDegrees);
  // Judged on the remeshed surface, which keeps within its distance bound of each face.
  EXPECT_LE(fit.thinnest_wall, side);
  EXPECT_GE(fit.thinnest_wall, side - 2.0 * fit.remesh->distance_bound);
  EXPECT_EQ(fit.narrowest_gap, INFINITY);
}

// A 150 Å box under a 40 Å bilayer: rounding its creases would leave a blob. The size given is the
// one at which the same stages, run again, find that it fits.
TEST(MembraneFit, ASmallBoxIsTooSmallForItsCreasesAndSaysACheckedSize) {
  ProxyMesh m;
  add_box(m, glm::dvec3(0.0), glm::dvec3(150.0));
  const MembraneFit fit = judge(m, 40.0);
  ASSERT_FALSE(fit.fits());
  EXPECT_TRUE(fit.remesh.has_value()) << "judged on the remeshed surface";
  EXPECT_EQ(fit.tight.front().what, "rounding");
  EXPECT_GT(fit.tight.front().needed, kMaxRoundingAreaLoss);
  EXPECT_FALSE(fit.has_defect());
  ASSERT_TRUE(fit.size_checked);
  EXPECT_GT(fit.scale_needed, 1.0);
  ProxyMesh larger;
  add_box(larger, glm::dvec3(0.0), glm::dvec3(150.0 * fit.scale_needed));
  EXPECT_TRUE(judge(larger, 40.0).fits()) << "the size given must work";
  const std::string text = describe_tight_features(fit, 40.0, 900.0);
  EXPECT_NE(text.find("the whole mesh: rounding its creases for the bilayer takes"), std::string::npos) << text;
  EXPECT_NE(text.find("\"diameter\": " + std::to_string(int(std::ceil(900.0 * fit.scale_needed))) + " Å or more (checked"),
            std::string::npos)
      << text;
  EXPECT_NE(describe_tight_features(fit, 40.0, std::nullopt).find("scaled by"), std::string::npos);
}

TEST(MembraneFit, AWallThinnerThanTheBilayerIsNamedAndAFittingSizeChecked) {
  // A fine sphere of radius 15 Å: every wall is a diameter, 30 Å, under a 40 Å bilayer.
  const MembraneFit fit = judge(make_sphere_mesh(2000, 15.0), 40.0);
  ASSERT_FALSE(fit.fits());
  EXPECT_EQ(fit.tight.front().what, "wall");
  EXPECT_NEAR(fit.tight.front().found, 30.0, 0.5);
  EXPECT_EQ(fit.tight.size(), 1u) << "one place: the whole sphere's tight triangles touch";
  ASSERT_TRUE(fit.size_checked);
  // The walls alone would fit at 40/30; the checked size also keeps the sphere's bend within the
  // kMinBendBilayers radius the shells take, which for a sphere is the stricter of the two.
  EXPECT_GE(fit.scale_needed, kMinBendBilayers * 40.0 / 15.0);
  EXPECT_LT(fit.scale_needed, 1.1 * kMinBendBilayers * 40.0 / 15.0);
  EXPECT_TRUE(judge(make_sphere_mesh(2000, 15.0 * fit.scale_needed), 40.0).fits());
  EXPECT_FALSE(judge(make_sphere_mesh(2000, 15.0 * kMinBendBilayers * 40.0 / 15.0 * 0.97), 40.0).fits());
  const std::string text = describe_tight_features(fit, 40.0, 30.0);
  EXPECT_NE(text.find("a wall 29.9 Å thick (the bilayer needs 40.0 Å)"), std::string::npos) << text;
}

// Two sheets 0.5 Å apart: a near-contact no plausible size cures, named as a defect at its place, and
// no diameter is given.
TEST(MembraneFit, ANearContactIsADefectNamedWhereItIs) {
  ProxyMesh m = make_sphere_mesh(4000, 300.0);
  const ProxyMesh other = make_sphere_mesh(4000, 300.0);
  const std::uint32_t first = static_cast<std::uint32_t>(m.positions.size());
  for (const glm::dvec3& p : other.positions) m.positions.push_back(p + glm::dvec3(601.0, 0.0, 0.0));
  for (const Triangle& t : other.triangles) m.triangles.push_back({first + t[0], first + t[1], first + t[2]});
  m.uvs.clear(), m.uv_triangles.clear(), m.normals.clear(), m.normal_triangles.clear();
  const MembraneFit fit = judge(m, 40.0);
  ASSERT_FALSE(fit.fits());
  ASSERT_TRUE(fit.has_defect());
  EXPECT_EQ(fit.tight.front().what, "gap");
  EXPECT_TRUE(fit.tight.front().defect);
  EXPECT_NEAR(fit.tight.front().position.x, 300.5, 30.0) << "named where the spheres nearly touch";
  const std::string text = describe_tight_features(fit, 40.0, 1201.0);
  EXPECT_NE(text.find("a defect of the mesh"), std::string::npos) << text;
  EXPECT_EQ(text.find("\"diameter\""), std::string::npos) << "no size cures a near-contact: none is given";
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
  const MembraneFit fit = fit_membrane(m, report, 40.0, off, "m.obj");
  EXPECT_TRUE(fit.fits()) << "the scene keeps its mesh: the shells judge it";
  EXPECT_FALSE(fit.remesh.has_value());
}

// A box with a hole needs its creases rounded, and remeshing does not guess at a shape: refused
// from the source the caller names, with the first problem; remesh_needed says why it would remesh.
TEST(MembraneFit, AMeshToRemeshWithAHoleIsRefusedNamingTheSource) {
  ProxyMesh m;
  add_box(m, glm::dvec3(0.0), glm::dvec3(400.0));
  m.triangles.pop_back();
  MeshReport report = check_mesh(m, {});
  EXPECT_TRUE(remesh_needed(m, report, RemeshPolicy{}).has_value());
  try {
    fit_membrane(m, report, 40.0, RemeshPolicy{}, {"box.obj", "compartment 'c'"});
    ADD_FAILURE() << "remeshed a box with a hole";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "box.obj");
    EXPECT_EQ(e.where(), "compartment 'c'");
    EXPECT_EQ(e.rule().rfind("cannot remesh a mesh with a ", 0), 0u) << e.what();
  }
  RemeshPolicy off;
  off.mode = RemeshPolicy::Mode::off;
  EXPECT_FALSE(remesh_needed(m, report, off).has_value());
}

}  // namespace
}  // namespace nano::mesh
