// Ray–sphere (RTG ch. 7 form) vs the quadratic solved in double (long double for the reference roots),
// with origins 10^6 Å away, grazing rays and non-normalised directions.
#include <gtest/gtest.h>

#include "shared/ray_sphere.h"
#include "test_util.hpp"

namespace {
using namespace placement_test;
using nano::gpu::sphere_intersect;

// Reference in long double on the float inputs: roots of |o + t d − c|² = r².
bool reference(glm::vec3 o, glm::vec3 d, glm::vec3 c, float r, long double& t0, long double& t1, long double& miss_margin) {
  long double f[3], dd[3];
  for (int i = 0; i < 3; ++i) f[i] = (long double)o[i] - c[i], dd[i] = d[i];
  long double a = 0, b = 0, cc = 0;
  for (int i = 0; i < 3; ++i) a += dd[i] * dd[i], b += f[i] * dd[i], cc += f[i] * f[i];
  // perpendicular distance² = |f|² − b²/a
  long double perp2 = cc - b * b / a;
  miss_margin = (long double)r * r - perp2;  // > 0: hit
  if (miss_margin < 0) return false;
  long double s = std::sqrt(a * miss_margin);
  t0 = (-b - s) / a;
  t1 = (-b + s) / a;
  return true;
}

void run(Rng& rng, double distance, bool grazing, double& worst, int& ambiguous, int n) {
  for (int i = 0; i < n; ++i) {
    float r = float(rng.uniform(0.8, 2.5));  // atom radii
    glm::vec3 c = rng.in_box(-5, 5);
    glm::vec3 dir = rng.unit_vector();
    glm::vec3 o = c - dir * float(distance * rng.uniform(0.5, 1.0));
    // aim at a point near the sphere; grazing rays pass at distance ≈ r
    glm::vec3 side = glm::normalize(glm::cross(dir, rng.unit_vector()));
    float miss = grazing ? r * float(1.0 + rng.uniform(-1e-3, 1e-3)) : r * float(rng.uniform(0, 1.3));
    glm::vec3 target = c + side * miss;
    glm::vec3 d = (target - o) * float(std::pow(10.0, rng.uniform(-3, 3)) / std::max(distance, 1.0));
    long double t0, t1, margin;
    bool want = reference(o, d, c, r, t0, t1, margin);
    float n0, n1;
    bool got = sphere_intersect(o, d, c, r, n0, n1);
    // hit/miss may legitimately differ only within float resolution of the perpendicular distance
    // (o − c) is rounded to float: ~1 ulp(distance) per component moves the line by that much
    double tol_margin = 4 * 1.2e-7 * distance * r + 1e-5 * r * r;
    if (std::abs((double)margin) < tol_margin) {
      ++ambiguous;
      continue;
    }
    ASSERT_EQ(got, want) << "distance " << distance << " margin " << (double)margin;
    if (!want) continue;
    ASSERT_LE(n0, n1);
    // error relative to |t| and to the t-extent of the sphere (r/|d|)
    long double scale = std::max(std::abs(t0), std::abs(t1)) + (long double)r / glm::length(glm::dvec3(d));
    double e0 = double(std::abs(n0 - t0) / scale), e1 = double(std::abs(n1 - t1) / scale);
    // near-tangent rays: the roots split as √margin, condition number ∝ r/√margin
    long double cond = std::max((long double)1, std::sqrt((long double)r * r / std::abs(margin)));
    e0 /= double(cond);
    e1 /= double(cond);
    worst = std::max({worst, e0, e1});
  }
}

TEST(RaySphere, NearRaysMatchDouble) {
  Rng rng(41);
  double worst = 0;
  int amb = 0;
  run(rng, 20, false, worst, amb, 20000);
  EXPECT_LT(worst, 1e-6);
  EXPECT_LT(amb, 20);
  std::printf("ray-sphere near: max condition-scaled rel t error %.3g (ambiguous %d)\n", worst, amb);
}

TEST(RaySphere, FarOrigin1e6MatchesDouble) {
  Rng rng(42);
  double worst = 0;
  int amb = 0;
  run(rng, 1e6, false, worst, amb, 20000);
  EXPECT_LT(worst, 1e-6);
  std::printf("ray-sphere at 1e6 A: max condition-scaled rel t error %.3g (ambiguous %d)\n", worst, amb);
  // The textbook b²−4ac in float loses the hit entirely at this distance; make sure we do not:
  glm::vec3 o(1e6f, 0, 0), d(-1, 0, 0), c(0, 0.5f, 0);
  float t0, t1;
  ASSERT_TRUE(sphere_intersect(o, d, c, 1.5f, t0, t1));
  EXPECT_NEAR(t0, 1e6f - std::sqrt(1.5f * 1.5f - 0.25f), 0.07f);  // float ulp at 1e6 is 0.0625
  EXPECT_NEAR(t1, 1e6f + std::sqrt(1.5f * 1.5f - 0.25f), 0.07f);
}

TEST(RaySphere, GrazingRaysConditionScaled) {
  Rng rng(43);
  double worst = 0;
  int amb = 0;
  run(rng, 30, true, worst, amb, 20000);
  EXPECT_LT(worst, 2e-6);
  std::printf("ray-sphere grazing: max condition-scaled t error %.3g (ambiguous %d of 20000)\n", worst, amb);
}

TEST(RaySphere, OriginInsideAndAxisAlignedAndDegenerate) {
  float t0, t1;
  ASSERT_TRUE(sphere_intersect(glm::vec3(0), glm::vec3(0, 0, 2), glm::vec3(0), 1.0f, t0, t1));
  EXPECT_FLOAT_EQ(t0, -0.5f);
  EXPECT_FLOAT_EQ(t1, 0.5f);
  ASSERT_TRUE(sphere_intersect(glm::vec3(0, 1, -5), glm::vec3(0, -0.0f, 1), glm::vec3(0), 1.0f, t0, t1));  // tangent
  EXPECT_FLOAT_EQ(t0, 5.0f);
  EXPECT_FLOAT_EQ(t1, 5.0f);
  EXPECT_FALSE(sphere_intersect(glm::vec3(0, 1.0001f, -5), glm::vec3(0, 0, 1), glm::vec3(0), 1.0f, t0, t1));
  EXPECT_FALSE(sphere_intersect(glm::vec3(0), glm::vec3(0), glm::vec3(0), 1.0f, t0, t1));  // d = 0
  // origin exactly at the centre, β = 0
  ASSERT_TRUE(sphere_intersect(glm::vec3(3), glm::vec3(1, 0, 0), glm::vec3(3), 2.0f, t0, t1));
  EXPECT_FLOAT_EQ(t0, -2.0f);
  EXPECT_FLOAT_EQ(t1, 2.0f);
}
}  // namespace
