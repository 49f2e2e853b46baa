// shell_prism.h against hand-computed prisms: the cap vertices along the vertex normals, the in-plane
// growth from offset edge lines (computed here by intersecting the lines, not by the bisector
// formula), the sliver clamp and the componentwise maximum.
#include <cmath>

#include <gtest/gtest.h>

#include "shared/shell_prism.h"

namespace g = nano::gpu;
using glm::dvec3;
using glm::vec3;

namespace {

void expect_near(const vec3& got, const dvec3& want, double tol = 1e-5) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

// Intersection of the in-plane (z = const) lines {x : n1·x = c1} and {x : n2·x = c2}.
dvec3 meet(glm::dvec2 n1, double c1, glm::dvec2 n2, double c2, double z) {
  const double det = n1.x * n2.y - n1.y * n2.x;
  return dvec3((c1 * n2.y - c2 * n1.y) / det, (n1.x * c2 - n2.x * c1) / det, z);
}

}  // namespace

TEST(ShellPrism, EquilateralFaceParallelNormals) {
  // Side L, centroid at the origin; every vertex moves radially by side / sin 30° = 2·side.
  const double L = 10.0, R = L / std::sqrt(3.0);
  vec3 p[3];
  for (int i = 0; i < 3; ++i) {
    const double a = 2.0 * M_PI * i / 3.0;
    p[i] = vec3(float(R * std::cos(a)), float(R * std::sin(a)), 0.f);
  }
  const vec3 n(0.f, 0.f, 1.f);
  const g::ShellOffsets off{3.f, 2.f, 0.5f};
  const g::Prism pr = g::shell_prism_make(p[0], p[1], p[2], n, n, n, off);
  for (int i = 0; i < 3; ++i) {
    const dvec3 radial = glm::normalize(dvec3(p[i]));
    expect_near(pr.v[i], dvec3(p[i]) + 2.0 * 0.5 * radial - dvec3(0, 0, 2.0));
    expect_near(pr.v[i + 3], dvec3(p[i]) + 2.0 * 0.5 * radial + dvec3(0, 0, 3.0));
  }
  // Each grown edge lies at inradius + side from the centroid.
  for (int cap = 0; cap < 2; ++cap)
    for (int e = 0; e < 3; ++e) {
      const dvec3 a(pr.v[cap * 3 + e]), b(pr.v[cap * 3 + (e + 1) % 3]);
      const dvec3 mid = 0.5 * (a + b);
      EXPECT_NEAR(std::hypot(mid.x, mid.y), L / (2.0 * std::sqrt(3.0)) + 0.5, 1e-5);
    }
}

TEST(ShellPrism, RightTriangleMatchesOffsetLineIntersections) {
  const vec3 p0(0, 0, 0), p1(4, 0, 0), p2(0, 4, 0), n(0, 0, 1);
  const double side = 1.0;
  const g::Prism pr = g::shell_prism_make(p0, p1, p2, n, n, n, g::ShellOffsets{1.f, 0.f, float(side)});
  // Edges (outward normal · x = c): y = 0 → −y ≤ 0; x = 0 → −x ≤ 0; x + y = 4 → (x+y)/√2 ≤ 4/√2.
  const glm::dvec2 nb(0, -1), nl(-1, 0), nh(1 / std::sqrt(2.0), 1 / std::sqrt(2.0));
  const double cb = side, cl = side, ch = 4 / std::sqrt(2.0) + side;
  for (int cap = 0; cap < 2; ++cap) {
    const double z = cap == 0 ? 0.0 : 1.0;
    expect_near(pr.v[cap * 3 + 0], meet(nb, cb, nl, cl, z));
    expect_near(pr.v[cap * 3 + 1], meet(nb, cb, nh, ch, z));
    expect_near(pr.v[cap * 3 + 2], meet(nl, cl, nh, ch, z));
  }
  expect_near(pr.v[1], dvec3(5.0 + std::sqrt(2.0), -1.0, 0.0));  // the hand value of the line meet
}

TEST(ShellPrism, CapsFollowTiltedVertexNormalsWithoutSide) {
  const vec3 p0(0, 0, 0), p1(6, 0, 0), p2(0, 5, 0);
  const vec3 n0 = glm::normalize(vec3(-0.3f, -0.2f, 1.f)), n1 = glm::normalize(vec3(0.4f, 0.f, 1.f)),
             n2 = glm::normalize(vec3(0.f, 0.5f, 1.f));
  const g::Prism pr = g::shell_prism_make(p0, p1, p2, n0, n1, n2, g::ShellOffsets{7.f, 3.f, 0.f});
  const vec3 p[3] = {p0, p1, p2}, n[3] = {n0, n1, n2};
  for (int i = 0; i < 3; ++i) {
    expect_near(pr.v[i], dvec3(p[i]) - 3.0 * dvec3(n[i]));
    expect_near(pr.v[i + 3], dvec3(p[i]) + 7.0 * dvec3(n[i]));
  }
}

TEST(ShellPrism, SliverCornerIsClamped) {
  // Corner angle atan(0.1) ≈ 5.7°: the exact miter 1/sin(2.85°) ≈ 20 is clamped to kShellMaxMiter.
  const vec3 p0(0, 0, 0), p1(10, 0, 0), p2(10, 1, 0), n(0, 0, 1);
  const double side = 0.25;
  const g::Prism pr = g::shell_prism_make(p0, p1, p2, n, n, n, g::ShellOffsets{0.f, 0.f, float(side)});
  const dvec3 bisector = glm::normalize(glm::normalize(dvec3(p1)) + glm::normalize(dvec3(p2)));
  expect_near(pr.v[0], -double(g::kShellMaxMiter) * side * bisector);
  // The right-angle corner at p1 is exact: both its edges move by `side` (x = 10 + side, y = −side).
  expect_near(pr.v[1], meet({0, -1}, side, {1, 0}, 10 + side, 0.0));
}

TEST(ShellPrism, DegenerateCornerDoesNotMove) {
  const vec3 p(1, 2, 3);
  EXPECT_EQ(g::shell_miter_offset(p, p, vec3(4, 5, 6), 1.f), vec3(0.f));
  EXPECT_EQ(g::shell_miter_offset(vec3(1, 0, 0), vec3(0, 0, 0), vec3(2, 0, 0), 1.f), vec3(0.f));  // 180°
}

TEST(ShellPrism, RayThroughFaceParallelPrismSeesBothCaps) {
  // The vertex order is the one prism_intersect expects: a vertical ray enters at −h_minus, exits at +h_plus.
  const vec3 n(0, 0, 1);
  const g::Prism pr = g::shell_prism_make(vec3(0, 0, 0), vec3(4, 0, 0), vec3(0, 4, 0), n, n, n,
                                          g::ShellOffsets{3.f, 2.f, 0.5f});
  g::PrismInterval r;
  ASSERT_TRUE(g::prism_intersect(pr, vec3(1, 1, -10), vec3(0, 0, 1), 0.f, 100.f, r));
  EXPECT_NEAR(r.t_enter, 8.0, 1e-4);
  EXPECT_NEAR(r.t_exit, 13.0, 1e-4);
  // Inside the overlap band only thanks to `side`: x = −0.3 lies outside the base triangle.
  ASSERT_TRUE(g::prism_intersect(pr, vec3(-0.3f, 1, -10), vec3(0, 0, 1), 0.f, 100.f, r));
}

TEST(ShellPrism, OffsetsMaxIsComponentwise) {
  const g::ShellOffsets m = g::shell_offsets_max(g::ShellOffsets{1.f, 5.f, 0.f}, g::ShellOffsets{2.f, 3.f, 0.5f});
  EXPECT_EQ(m.h_plus, 2.f);
  EXPECT_EQ(m.h_minus, 5.f);
  EXPECT_EQ(m.side, 0.5f);
}
