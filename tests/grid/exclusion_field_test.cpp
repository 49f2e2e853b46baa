// The exclusion field against brute force: node values against the distance to every triangle
// less that triangle's reach (side from the analytic shape), and the medium's rule against the true
// clearance at random points: interpolated value minus the margin never claims more room than there
// is, and stays close to it where the rule decides. A patch of tall triangles (spikes) keeps the
// medium away from itself only.
#include "bake/grid/exclusion_field.hpp"

#include <cmath>
#include <optional>
#include <functional>
#include <random>

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include "bake/grid/triangle_distance.hpp"
#include "bake/mesh/sphere_mesh.hpp"
#include "common/error.hpp"

namespace nano::grid {
namespace {

double brute_distance(const mesh::ProxyMesh& m, const glm::dvec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : m.triangles)
    best = std::min(best, squared_distance_to_triangle(p, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
  return std::sqrt(best);
}

// What the field's values mean, triangle by triangle: outside, the least over every triangle of its
// distance less its reach; inside, that less twice the distance to the mesh.
double brute_clearance(const mesh::ProxyMesh& m, const std::vector<float>& reach, const glm::dvec3& p, bool inside) {
  if (inside) return brute_clearance(m, reach, p, false) - 2 * brute_distance(m, p);
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const auto& t = m.triangles[i];
    best = std::min(best, std::sqrt(squared_distance_to_triangle(p, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]])) - reach[i]);
  }
  return best;
}

// A cube of edge 2·h centred on the origin, two triangles a face, outward.
mesh::ProxyMesh cube(double h) {
  mesh::ProxyMesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back({i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h});
  m.triangles = {{{0, 2, 1}}, {{1, 2, 3}}, {{4, 5, 6}}, {{5, 7, 6}}, {{0, 1, 4}}, {{1, 5, 4}},
                 {{2, 6, 3}}, {{3, 6, 7}}, {{0, 4, 2}}, {{2, 4, 6}}, {{1, 3, 5}}, {{3, 7, 5}}};
  return m;
}

struct Shape {
  mesh::ProxyMesh mesh;
  // The side of p when the analytic shape knows it for sure (nullopt within the facets' sag).
  std::function<std::optional<bool>(const glm::dvec3&)> inside;
};

Shape sphere_shape() {
  const double r = 500;
  // Every facet's plane lies within 1.5 % of the radius for this tessellation (checked below).
  return {mesh::make_sphere_mesh(3000, r), [r](const glm::dvec3& p) -> std::optional<bool> {
            const double d = glm::length(p);
            if (d < 0.97 * r) return true;
            if (d > r + 1e-6) return false;
            return std::nullopt;
          }};
}

Shape cube_shape() {
  const double h = 400;
  return {cube(h), [h](const glm::dvec3& p) -> std::optional<bool> {
            const double m = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
            if (std::abs(m - h) < 1e-6) return std::nullopt;
            return m < h;
          }};
}

constexpr float kLipidReach = 40.f, kSpikeReach = 150.f;

ExclusionFieldRequest request(const Shape& s, std::size_t nodes) {
  ExclusionFieldRequest r;
  r.reach.assign(s.mesh.triangles.size(), kLipidReach);
  r.medium_reach = 60;
  r.max_nodes = nodes;
  r.threads = 2;
  return r;
}

// Triangles whose centroid lies above z = 0.8·radius reach kSpikeReach.
ExclusionFieldRequest spiked_request(const Shape& s, std::size_t nodes) {
  ExclusionFieldRequest r = request(s, nodes);
  for (std::size_t t = 0; t < s.mesh.triangles.size(); ++t) {
    glm::dvec3 centroid(0.0);
    for (int c = 0; c < 3; ++c) centroid += s.mesh.corner_position(t, c) / 3.0;
    if (centroid.z > 0.8 * 500) r.reach[t] = kSpikeReach;
  }
  return r;
}

void expect_nodes_exact(const Shape& s, const ExclusionField& f, const std::vector<float>& reach) {
  int checked = 0;
  for (int k = 0; k < f.dims.z; k += 3)
    for (int j = 0; j < f.dims.y; j += 2)
      for (int i = 0; i < f.dims.x; ++i) {
        const glm::dvec3 p = f.origin + f.spacing * glm::dvec3(i, j, k);
        const std::optional<bool> inside = s.inside(p);
        if (!inside) continue;
        const double expected = std::clamp(brute_clearance(s.mesh, reach, p, *inside), -f.clamp, f.clamp);
        ASSERT_NEAR(f.values[f.node_index(i, j, k)], expected, 1e-3 * (1 + std::abs(expected))) << "node " << i << "," << j << "," << k;
        ++checked;
      }
  EXPECT_GT(checked, 1000);
}

// At random points of the grid: wherever the rule's value reaches a threshold the medium can ask
// (0 to reach), the truth reaches it too; where the truth is in that range, the rule understates it
// by at most `slack`.
void expect_rule_safe_and_tight(const Shape& s, const ExclusionField& f, const std::vector<float>& triangle_reach, double reach,
                                double slack) {
  const double shell = *std::max_element(triangle_reach.begin(), triangle_reach.end());
  std::mt19937_64 rng(7);
  const glm::dvec3 top = f.origin + f.spacing * glm::dvec3(f.dims - 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int decided = 0;
  double worst_under = 0;
  for (int n = 0; n < 20000; ++n) {
    // Half the points near the surface, where decisions are made.
    glm::dvec3 p = f.origin + (top - f.origin) * glm::dvec3(u(rng), u(rng), u(rng));
    if (n % 2 == 0) {
      const glm::dvec3 on = s.mesh.positions[rng() % s.mesh.positions.size()];
      p = on + glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5) * (2.0 * (shell + reach + f.spacing));
    }
    const std::optional<bool> inside = s.inside(p);
    if (!inside) continue;
    const double truth = brute_clearance(s.mesh, triangle_reach, p, *inside);
    const double rule = interpolated_clearance(f, p) - f.margin;
    // Deep inside, interpolation across the medial axis overstates, harmlessly: the rule only ever
    // asks whether the value reaches a threshold in [0, reach].
    if (rule >= 0) {
      ASSERT_GE(truth, std::min(rule, reach) - 1e-3) << "at " << p.x << "," << p.y << "," << p.z << " (rule " << rule << ")";
    }
    if (truth >= 0 && truth <= reach) {
      ++decided;
      worst_under = std::max(worst_under, truth - rule);
    }
  }
  EXPECT_GT(decided, 500);
  EXPECT_LE(worst_under, slack) << "spacing " << f.spacing << ", margin " << f.margin;
}

// Bakes the field of `r` on s and holds it to brute force at its nodes and at random points, the
// rule allowed to understate by the margin and `spacings` node spacings.
ExclusionField expect_exact_and_safe(const Shape& s, const ExclusionFieldRequest& r, double spacings) {
  const MeshSurface surface(s.mesh);
  ExclusionField f = bake_exclusion_field(surface, r);
  expect_nodes_exact(s, f, r.reach);
  expect_rule_safe_and_tight(s, f, r.reach, 60, f.margin + spacings * f.spacing);
  return f;
}

TEST(ExclusionField, SphereNodesAreTheSignedDistanceLessTheShell) {
  const Shape s = sphere_shape();
  const MeshSurface surface(s.mesh);
  const ExclusionFieldRequest r = request(s, 40000);
  const ExclusionField f = bake_exclusion_field(surface, r);
  EXPECT_LE(std::size_t(f.dims.x) * f.dims.y * f.dims.z, 40000u);
  // The grid spans the mesh grown by shell + medium reach, and two spacings more.
  EXPECT_LE(f.origin.x, -500 - 100 - 2 * f.spacing + 1e-9);
  EXPECT_GE(f.origin.x + f.spacing * (f.dims.x - 1), 500 + 100 + 2 * f.spacing - 1e-9);
  EXPECT_EQ(f.least_reach, kLipidReach);
  EXPECT_EQ(f.largest_reach, kLipidReach);
  expect_nodes_exact(s, f, r.reach);
}

TEST(ExclusionField, SphereRuleNeverOverstatesTheRoom) {
  const Shape s = sphere_shape();
  const MeshSurface surface(s.mesh);
  const ExclusionFieldRequest r = request(s, 40000);
  const ExclusionField f = bake_exclusion_field(surface, r);
  EXPECT_GT(f.samples, 0u);
  expect_rule_safe_and_tight(s, f, r.reach, 60, f.margin + 0.1 * f.spacing);
}

TEST(ExclusionField, ACoarseGridWidensItsMarginAndStaysSafe) {
  // 3,000 nodes: a spacing of ~130 Å on a sphere of radius 500, so interpolation across the curve
  // overstates by several Å; the measured margin must cover it.
  const Shape s = sphere_shape();
  const MeshSurface surface(s.mesh);
  const ExclusionField fine = bake_exclusion_field(surface, request(s, 40000));
  const ExclusionFieldRequest r = request(s, 3000);
  const ExclusionField coarse = bake_exclusion_field(surface, r);
  EXPECT_GT(coarse.spacing, 3 * fine.spacing);
  EXPECT_GT(coarse.margin, fine.margin);
  expect_rule_safe_and_tight(s, coarse, r.reach, 60, coarse.margin + 0.1 * coarse.spacing);
}

TEST(ExclusionField, CubeEdgesAndCornersNeverOverstateTheRoom) {
  const Shape s = cube_shape();
  expect_exact_and_safe(s, request(s, 30000), 0.1);
}

TEST(ExclusionField, SpikesKeepTheMediumFromTheirOwnTriangles) {
  const Shape s = sphere_shape();
  const MeshSurface surface(s.mesh);
  const ExclusionFieldRequest r = spiked_request(s, 40000);
  // Where the spikes' reach gives way to the lipids' the field has a crease (a least of two slopes),
  // and trilinear interpolation cuts under a crease by up to half a spacing.
  const ExclusionField f = expect_exact_and_safe(s, r, 0.5);
  EXPECT_EQ(f.least_reach, kLipidReach);
  EXPECT_EQ(f.largest_reach, kSpikeReach);
  // 80 Å beyond the south pole the medium has 80 − 40 Å (the lipids' reach); the same height above
  // the spikes is inside their reach; beside the spike patch the spikes decide.
  const DrawnClearance clearance(surface, r.reach);
  const glm::dvec3 south(0, 0, -580), north(0, 0, 580);
  EXPECT_NEAR(clearance.at(south), brute_clearance(s.mesh, r.reach, south, false), 1e-9);
  EXPECT_NEAR(interpolated_clearance(f, south) - f.margin, brute_distance(s.mesh, south) - kLipidReach, f.margin + 1.0);
  EXPECT_GT(clearance.at(south), 30.0);
  EXPECT_LT(clearance.at(north), -60.0);
  const glm::dvec3 beside = glm::dvec3(std::sqrt(1 - 0.7 * 0.7), 0, 0.7) * 560.0;  // 60 Å out, below the patch
  EXPECT_NEAR(clearance.at(beside), brute_clearance(s.mesh, r.reach, beside, false), 1e-9);
  EXPECT_LT(clearance.at(beside), 60.0 - kLipidReach - 1.0);
}

// Spikes scattered one triangle each, as a virion's: fewer than the clearance tests one by one.
TEST(ExclusionField, ScatteredSpikesAreExactToo) {
  const Shape s = sphere_shape();
  const MeshSurface surface(s.mesh);
  ExclusionFieldRequest r = request(s, 20000);
  for (std::size_t t = 0; t < r.reach.size(); t += 150) r.reach[t] = kSpikeReach - float(t % 7);
  EXPECT_EQ(expect_exact_and_safe(s, r, 0.5).largest_reach, kSpikeReach);
  // Points around one spike, at random: the field's exact value against every triangle.
  const DrawnClearance clearance(surface, r.reach);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-250.0, 250.0);
  const glm::dvec3 spike = s.mesh.corner_position(300, 0);
  for (int n = 0; n < 400; ++n) {
    const glm::dvec3 p = spike * 1.2 + glm::dvec3(u(rng), u(rng), u(rng));
    const std::optional<bool> inside = s.inside(p);
    if (!inside) continue;
    ASSERT_NEAR(clearance.at(p), brute_clearance(s.mesh, r.reach, p, *inside), 1e-9) << p.x << "," << p.y << "," << p.z;
  }
}

TEST(ExclusionField, BeyondTheGridEveryPointIsClear) {
  const Shape s = cube_shape();
  const MeshSurface surface(s.mesh);
  const ExclusionField f = bake_exclusion_field(surface, request(s, 8000));
  EXPECT_EQ(interpolated_clearance(f, {1e5, 0, 0}), f.clamp);
  EXPECT_GE(f.clamp - f.margin, 60.0);  // a clear point passes every threshold the medium asks
  EXPECT_LT(interpolated_clearance(f, {0, 0, 0}), 0.0);
}

TEST(ExclusionField, ReachesMustBeOnePerTriangleFiniteAndNonNegative) {
  const Shape s = cube_shape();
  const MeshSurface surface(s.mesh);
  EXPECT_THROW(DrawnClearance(surface, std::vector<float>(5, 1.f)), InputError);
  std::vector<float> reach(s.mesh.triangles.size(), 10.f);
  reach[3] = -1.f;
  EXPECT_THROW(DrawnClearance(surface, reach), InputError);
  reach[3] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(DrawnClearance(surface, reach), InputError);
  // None: a compartment without a membrane keeps the medium off its mesh only.
  const DrawnClearance bare(surface, {});
  EXPECT_EQ(bare.largest_reach(), 0.0);
  EXPECT_NEAR(bare.at({500, 0, 0}), 100.0, 1e-9);
  EXPECT_NEAR(bare.at({0, 0, 0}), -400.0, 1e-9);
}

}  // namespace
}  // namespace nano::grid
