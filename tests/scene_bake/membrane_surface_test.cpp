// How a membrane's tiles meet its meshes (bake/scene_bake/membrane_surface.hpp): per-triangle
// measures against the whole-mesh ones, and the plan's three outcomes on spheres whose curvature is
// known analytically (turn rate 1/R).
#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "bake/mesh/sphere_mesh.hpp"
#include "bake/mesh/uv_distortion.hpp"
#include "bake/mesh/vertex_normals.hpp"
#include "bake/scene_bake/membrane_surface.hpp"

namespace {

using namespace nano;
using scene_bake::MembraneSurfacePlan;
using scene_bake::plan_membrane_surface;

constexpr double kSmooth = 0.5;

double area_of(const mesh::ProxyMesh& m) {
  double a = 0.0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) a += mesh::world_area(m, t);
  return a;
}

MembraneSurfacePlan plan_one(const mesh::ProxyMesh& m, double copies_per_a2, double budget) {
  const mesh::ProxyMesh* meshes[] = {&m};
  return plan_membrane_surface(meshes, copies_per_a2, kSmooth, budget, 2);
}

TEST(MembraneSurface, TriangleMeasuresAreTheMeshMeasuresTriangleByTriangle) {
  const mesh::ProxyMesh sphere = mesh::make_sphere_mesh(1452, 2000.0);
  const auto d = scene_bake::triangle_distortions(sphere, kSmooth, 2);
  ASSERT_EQ(d.size(), sphere.triangles.size());
  double turn = 0.0, tilt = 0.0, sag = 0.0, area = 0.0, minor = INFINITY, major = 0.0;
  for (const auto& t : d) {
    turn = std::max(turn, t.turn_rate);
    tilt = std::max(tilt, t.tilt);
    sag = std::max(sag, t.sag);
    area += t.area;
    minor = std::min(minor, t.minor);
    major = std::max(major, t.major);
  }
  EXPECT_EQ(turn, mesh::normal_turn_rate(sphere));
  EXPECT_EQ(tilt, mesh::largest_smooth_normal_tilt(sphere, kSmooth));
  EXPECT_EQ(sag, mesh::largest_facet_sag(sphere));
  EXPECT_NEAR(area, area_of(sphere), 1e-9 * area);
  EXPECT_EQ(minor, mesh::smallest_stretch(sphere));
  EXPECT_DOUBLE_EQ(major / minor, mesh::chart_anisotropy(sphere));
  EXPECT_NEAR(turn, 1.0 / 2000.0, 0.3 / 2000.0) << "a sphere's normals turn by about 1/R";
}

TEST(MembraneSurface, SmallMembraneIsPackedRigidAndCheckedEverywhere) {
  const mesh::ProxyMesh sphere = mesh::make_sphere_mesh(1452, 500.0);
  const MembraneSurfacePlan plan = plan_one(sphere, 0.03, 600000.0);  // ~94,000 copies
  EXPECT_TRUE(plan.whole_surface);
  EXPECT_TRUE(plan.pack_for.rigid());
  ASSERT_EQ(plan.meshes.size(), 1u);
  EXPECT_DOUBLE_EQ(plan.meshes[0].tile_scale, mesh::uv_scale(sphere)) << "rigid tiles take the chart's mean scale";
  EXPECT_DOUBLE_EQ(plan.checked_copies, plan.copies);
}

// A cell 20 µm across turns its normals by 10⁻⁴ rad/Å: within what tiles are packed for, so nothing
// is checked but the seams, and the tiles are packed for exactly what the mesh does.
TEST(MembraneSurface, LargeSmoothMembraneIsPackedForItsOwnDistortion) {
  const mesh::ProxyMesh sphere = mesh::make_sphere_mesh(1452, 1e5);
  const MembraneSurfacePlan plan = plan_one(sphere, 0.03, 600000.0);
  ASSERT_FALSE(plan.whole_surface);
  const auto& m = plan.meshes[0];
  EXPECT_EQ(std::count(m.checked.begin(), m.checked.end(), 1), 0);
  EXPECT_EQ(m.tile_scale, mesh::smallest_stretch(sphere)) << "never compressed where nothing checks the copies";
  EXPECT_FLOAT_EQ(plan.pack_for.curvature, float(1.05 * mesh::normal_turn_rate(sphere)));
  EXPECT_FLOAT_EQ(plan.pack_for.lateral_stretch, float(mesh::chart_anisotropy(sphere) - 1.0));
  EXPECT_FLOAT_EQ(plan.pack_for.tilt, float(mesh::largest_smooth_normal_tilt(sphere, kSmooth)));
  EXPECT_EQ(plan.checked_copies, 0.0);
}

// The same cell with a dent at its pole (its corner normals turned 30°): the dented triangles are
// checked copy by copy, and the tiles are packed for the rest only.
TEST(MembraneSurface, TightPartIsCheckedNotPackedFor) {
  mesh::ProxyMesh sphere = mesh::make_sphere_mesh(1452, 1e5);
  const glm::dquat turn = glm::angleAxis(glm::radians(30.0), glm::dvec3(1.0, 0.0, 0.0));
  std::vector<char> dented(sphere.normals.size(), 0);
  for (std::size_t t = 0; t < sphere.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c)
      if (sphere.corner_position(t, c).z > 0.95e5) dented[sphere.normal_triangles[t][c]] = 1;
  for (std::size_t n = 0; n < sphere.normals.size(); ++n)
    if (dented[n]) sphere.normals[n] = turn * sphere.normals[n];
  const MembraneSurfacePlan plan = plan_one(sphere, 0.03, 600000.0);
  ASSERT_FALSE(plan.whole_surface);
  const auto& m = plan.meshes[0];
  const auto d = scene_bake::triangle_distortions(sphere, kSmooth, 1);
  double tight_area = 0.0;
  for (std::size_t t = 0; t < d.size(); ++t) {
    const bool tight = d[t].turn_rate > scene_bake::kPackableDistortion.turn_rate || d[t].tilt > scene_bake::kPackableDistortion.tilt;
    if (tight) {
      tight_area += d[t].area;
      EXPECT_EQ(m.checked[t], 1) << "triangle " << t << " distorts beyond the limits but is not checked";
    }
  }
  ASSERT_GT(tight_area, 0.0);
  EXPECT_LT(tight_area, 0.2 * m.area);
  EXPECT_GE(m.checked_area, tight_area);
  EXPECT_LE(plan.pack_for.curvature, float(1.05 * scene_bake::kPackableDistortion.turn_rate));
  EXPECT_LE(plan.pack_for.tilt, float(scene_bake::kPackableDistortion.tilt));
  EXPECT_NEAR(plan.checked_copies, 0.03 * m.checked_area, 1e-6 * plan.checked_copies);
}

// A membrane too large to check everywhere on a surface curved beyond the limits almost everywhere
// (a 2,000 Å sphere: 5·10⁻⁴ rad/Å is its own turn rate): checked everywhere, tiles rigid.
TEST(MembraneSurface, MostlyTightMembraneIsCheckedEverywhere) {
  const mesh::ProxyMesh sphere = mesh::make_sphere_mesh(1452, 1500.0);
  const MembraneSurfacePlan plan = plan_one(sphere, 0.03, 1000.0);
  EXPECT_TRUE(plan.whole_surface);
  EXPECT_TRUE(plan.pack_for.rigid());
  EXPECT_DOUBLE_EQ(plan.meshes[0].tile_scale, mesh::uv_scale(sphere));
}

}  // namespace
