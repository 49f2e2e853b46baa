// The exclusion field against brute force: node values against the distance to every triangle
// (sign from the analytic shape), and the medium's rule against the true clearance at random
// points: interpolated value minus the margin never claims more room than there is, and stays close
// to it where the rule decides.
#include "bake/grid/exclusion_field.hpp"

#include <cmath>
#include <optional>
#include <functional>
#include <random>

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include "bake/grid/triangle_distance.hpp"
#include "bake/mesh/sphere_mesh.hpp"

namespace nano::grid {
namespace {

double brute_distance(const mesh::ProxyMesh& m, const glm::dvec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : m.triangles)
    best = std::min(best, squared_distance_to_triangle(p, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
  return std::sqrt(best);
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

ExclusionFieldRequest request(std::size_t nodes) {
  ExclusionFieldRequest r;
  r.shell_reach = 40;
  r.medium_reach = 60;
  r.max_nodes = nodes;
  r.threads = 2;
  return r;
}

void expect_nodes_exact(const Shape& s, const ExclusionField& f, double shell) {
  int checked = 0;
  for (int k = 0; k < f.dims.z; k += 3)
    for (int j = 0; j < f.dims.y; j += 2)
      for (int i = 0; i < f.dims.x; ++i) {
        const glm::dvec3 p = f.origin + f.spacing * glm::dvec3(i, j, k);
        const std::optional<bool> inside = s.inside(p);
        if (!inside) continue;
        const double d = brute_distance(s.mesh, p);
        const double expected = std::clamp((*inside ? -d : d) - shell, -f.clamp, f.clamp);
        ASSERT_NEAR(f.values[f.node_index(i, j, k)], expected, 1e-3 * (1 + std::abs(expected))) << "node " << i << "," << j << "," << k;
        ++checked;
      }
  EXPECT_GT(checked, 1000);
}

// At random points of the grid: wherever the rule's value reaches a threshold the medium can ask
// (0 to reach), the truth reaches it too; where the truth is in that range, the rule understates it
// by at most `slack`.
void expect_rule_safe_and_tight(const Shape& s, const ExclusionField& f, double shell, double reach, double slack) {
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
    const double d = brute_distance(s.mesh, p);
    const double truth = (*inside ? -d : d) - shell;
    const double rule = interpolated_clearance(f, p) - f.margin;
    // Deep inside, interpolation across the medial axis overstates, harmlessly: the rule only ever
    // asks whether the value reaches a threshold in [0, reach].
    if (rule >= 0) ASSERT_GE(truth, std::min(rule, reach) - 1e-3) << "at " << p.x << "," << p.y << "," << p.z << " (rule " << rule << ")";
    if (truth >= 0 && truth <= reach) {
      ++decided;
      worst_under = std::max(worst_under, truth - rule);
    }
  }
  EXPECT_GT(decided, 500);
  EXPECT_LE(worst_under, slack) << "spacing " << f.spacing << ", margin " << f.margin;
}

TEST(ExclusionField, SphereNodesAreTheSignedDistanceLessTheShell) {
  const Shape s = sphere_shape();
  const MeshSurface surface(s.mesh);
  const ExclusionField f = bake_exclusion_field(surface, request(40000));
  EXPECT_LE(std::size_t(f.dims.x) * f.dims.y * f.dims.z, 40000u);
  // The grid spans the mesh grown by shell + medium reach, and two spacings more.
  EXPECT_LE(f.origin.x, -500 - 100 - 2 * f.spacing + 1e-9);
  EXPECT_GE(f.origin.x + f.spacing * (f.dims.x - 1), 500 + 100 + 2 * f.spacing - 1e-9);
  expect_nodes_exact(s, f, 40);
}

TEST(ExclusionField, SphereRuleNeverOverstatesTheRoom) {
  const Shape s = sphere_shape();
  const MeshSurface surface(s.mesh);
  const ExclusionField f = bake_exclusion_field(surface, request(40000));
  EXPECT_GT(f.samples, 0u);
  expect_rule_safe_and_tight(s, f, 40, 60, f.margin + 0.1 * f.spacing);
}

TEST(ExclusionField, ACoarseGridWidensItsMarginAndStaysSafe) {
  // 3,000 nodes: a spacing of ~130 Å on a sphere of radius 500, so interpolation across the curve
  // overstates by several Å; the measured margin must cover it.
  const Shape s = sphere_shape();
  const MeshSurface surface(s.mesh);
  const ExclusionField fine = bake_exclusion_field(surface, request(40000));
  const ExclusionField coarse = bake_exclusion_field(surface, request(3000));
  EXPECT_GT(coarse.spacing, 3 * fine.spacing);
  EXPECT_GT(coarse.margin, fine.margin);
  expect_rule_safe_and_tight(s, coarse, 40, 60, coarse.margin + 0.1 * coarse.spacing);
}

TEST(ExclusionField, CubeEdgesAndCornersNeverOverstateTheRoom) {
  const Shape s = cube_shape();
  const MeshSurface surface(s.mesh);
  const ExclusionField f = bake_exclusion_field(surface, request(30000));
  expect_nodes_exact(s, f, 40);
  expect_rule_safe_and_tight(s, f, 40, 60, f.margin + 0.1 * f.spacing);
}

TEST(ExclusionField, BeyondTheGridEveryPointIsClear) {
  const Shape s = cube_shape();
  const MeshSurface surface(s.mesh);
  const ExclusionField f = bake_exclusion_field(surface, request(8000));
  EXPECT_EQ(interpolated_clearance(f, {1e5, 0, 0}), f.clamp);
  EXPECT_GE(f.clamp - f.margin, 60.0);  // a clear point passes every threshold the medium asks
  EXPECT_LT(interpolated_clearance(f, {0, 0, 0}), 0.0);
}

}  // namespace
}  // namespace nano::grid
