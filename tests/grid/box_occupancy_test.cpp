#include "bake/grid/box_occupancy.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "bake/mesh/rbc_mesh.hpp"
#include "bake/mesh/sphere_mesh.hpp"
#include "common/error.hpp"
#include "tests/grid/grid_oracles.hpp"

namespace nano::grid {
namespace {

double cubed(double x) { return x * x * x; }

// The mesh's surface lies in the shell R − δ ≤ |p| ≤ R (vertices on the sphere, flat triangles).
double sphere_deviation(const mesh::ProxyMesh& m, double radius) {
  double closest = radius;
  for (const mesh::Triangle& t : m.triangles)
    closest = std::min(closest, oracle::triangle_distance({0, 0, 0}, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
  return radius - closest;
}

TEST(BoxOccupancy, SphereAgainstAnalyticSphere) {
  const double R = 10000.0, S = 400.0, C = 300.0;
  const mesh::ProxyMesh m = mesh::make_sphere_mesh(5000, R);
  const double delta = sphere_deviation(m, R), hd = 0.5 * std::sqrt(3.0) * S, tol = 1e-6 * R;
  ASSERT_GT(delta, 0.0);
  ASSERT_LT(delta, 0.01 * R);
  const MeshSurface surface(m);
  const CoreGrid g = make_core_grid(m, S);
  const BoxOccupancy occ = classify_boxes(surface, g, C, 2);
  ASSERT_EQ(occ.classes.size(), g.box_count());
  EXPECT_EQ(occ.inside + occ.outside + occ.boundary, g.box_count());
  for (BoxIndex i = 0; i < g.box_count(); ++i) {
    const glm::ivec3 b = g.box_at(i);
    const glm::dvec3 lo = g.box_min(b);
    const double rmin = oracle::box_min_radius(lo, S), rmax = oracle::box_max_radius(lo, S);
    const double rc = glm::length(g.box_centre(b));
    switch (occ.classes[i]) {
      case BoxClass::inside:  // inside the mesh (⊂ ball R) and clear of it by C
        EXPECT_LT(rmax, R - C + tol) << i;
        break;
      case BoxClass::outside:  // outside the mesh (⊃ ball R − δ)
        EXPECT_GT(rmin, R - delta - tol) << i;
        break;
      case BoxClass::boundary:  // only where the box might meet the shell R − δ … R + C: not farther than hd from it
        EXPECT_GT(rc, R - delta - C - hd - tol) << i;
        EXPECT_LT(rc, R + hd + tol) << i;
        break;
    }
    // Completeness: a box whose centre is clearly in or out must not be BOUNDARY.
    if (rc < R - delta - C - hd - tol) {
      EXPECT_EQ(occ.classes[i], BoxClass::inside) << i;
    }
    if (rc > R + hd + tol) {
      EXPECT_EQ(occ.classes[i], BoxClass::outside) << i;
    }
  }
  // INSIDE volume: at most the ball R − C, at least the ball R − δ − C − 2·hd; close to R − C.
  const double volume = static_cast<double>(occ.inside) * cubed(S), ball = 4.0 / 3.0 * std::numbers::pi;
  EXPECT_LE(volume, ball * cubed(R - C));
  EXPECT_GE(volume, ball * cubed(R - delta - C - 2.0 * hd));
  EXPECT_NEAR(volume / (ball * cubed(R - C)), 1.0, 0.12);
  // Thread count does not change the result.
  EXPECT_EQ(classify_boxes(surface, g, C, 1).classes, occ.classes);
}

TEST(BoxOccupancy, RbcAgainstEvansFung) {
  const double S = 1000.0, C = 300.0;
  const mesh::ProxyMesh m = mesh::make_rbc_mesh(3000);
  const oracle::EvansFungDistance distance;
  // The mesh's deviation from the analytic surface, sampled densely on every triangle; the
  // sampled maximum is padded by half its value (the true maximum lies between samples).
  double delta = 0.0;
  for (const mesh::Triangle& t : m.triangles)
    for (int i = 0; i <= 6; ++i)
      for (int j = 0; i + j <= 6; ++j) {
        const glm::dvec3 p = m.positions[t[0]] + (i / 6.0) * (m.positions[t[1]] - m.positions[t[0]]) +
                             (j / 6.0) * (m.positions[t[2]] - m.positions[t[0]]);
        delta = std::max(delta, distance(p));
      }
  delta = 1.5 * delta + 1.0;
  ASSERT_LT(delta, 400.0);
  const MeshSurface surface(m);
  const CoreGrid g = make_core_grid(m, S);
  const BoxOccupancy occ = classify_boxes(surface, g, C, 2);
  const double hd = 0.5 * std::sqrt(3.0) * S;
  std::uint64_t checked_inside = 0, checked_outside = 0;
  for (BoxIndex i = 0; i < g.box_count(); ++i) {
    const glm::ivec3 b = g.box_at(i);
    const BoxClass cls = occ.classes[i];
    // Distance is 1-Lipschitz: samples of a box whose centre is deep enough need no own check.
    const bool deep = cls == BoxClass::inside && oracle::evans_fung(g.box_centre(b)) < 0.0 &&
                      distance(g.box_centre(b)) - hd >= C - delta;
    for (const glm::dvec3& p : oracle::box_samples(g.box_min(b), S)) {
      const bool in = oracle::evans_fung(p) < 0.0;
      if (cls == BoxClass::inside) {
        EXPECT_TRUE(in) << i;
        if (!deep) {
          EXPECT_GE(distance(p), C - delta) << i;
        }
      } else if (cls == BoxClass::outside && in) {
        EXPECT_LE(distance(p), delta) << i;  // only between the mesh and the analytic surface
      }
    }
    checked_inside += cls == BoxClass::inside;
    checked_outside += cls == BoxClass::outside;
  }
  // Completeness: a box whose centre is clearly inside (beyond C) or outside is never BOUNDARY.
  for (BoxIndex i = 0; i < g.box_count(); ++i) {
    const glm::dvec3 c = g.box_centre(g.box_at(i));
    const bool in = oracle::evans_fung(c) < 0.0;
    if (occ.classes[i] == (in ? BoxClass::inside : BoxClass::outside)) continue;
    const double margin = distance(c);
    EXPECT_LE(margin, hd + delta + (in ? C : 0.0) + 1.0) << i;
  }
  EXPECT_GT(checked_inside, 500u);
  EXPECT_GT(checked_outside, 1000u);
  // The dimple above and below the centre (half thickness 4051 Å on the axis) is outside.
  for (double z : {7000.0, 9000.0, -7000.0, -9000.0}) EXPECT_EQ(occ.at(g.box_of({1.0, 1.0, z})), BoxClass::outside) << z;
  EXPECT_NE(occ.at(g.box_of({1.0, 1.0, 0.0})), BoxClass::outside);
}

TEST(BoxOccupancy, BadInputThrows) {
  const mesh::ProxyMesh m = mesh::make_sphere_mesh(48, 100.0);
  const MeshSurface surface(m);
  const CoreGrid g = make_core_grid(m, 50.0);
  EXPECT_THROW(classify_boxes(surface, g, -1.0), InputError);
  EXPECT_THROW(classify_boxes(surface, g, std::nan("")), InputError);
  EXPECT_THROW(classify_boxes(surface, CoreGrid{}, 1.0), InputError);
}

}  // namespace
}  // namespace nano::grid
