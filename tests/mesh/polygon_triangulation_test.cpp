// How the readers triangulate a polygon face (bake/mesh/polygon_soup.cpp, mesh_reader.hpp's rules):
// 5 or more corners are cut, in the polygon's own plane, along diagonals inside it, so that the
// smallest angle is as large as it can be. Judged here independently: every triangulation of a
// convex polygon enumerated, areas and overlaps measured in the plane, point-in-polygon by the
// crossing rule.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "bake/mesh/mesh_reader.hpp"
#include "bake/mesh/polygon_soup.hpp"
#include "tests/mesh/test_obj.hpp"

namespace nano::mesh {
namespace {

using testing::TempDir;
using Index3 = std::array<std::size_t, 3>;
constexpr double kPi = std::numbers::pi;

// The polygon as one face of a soup, through the readers' one assembly step; its triangles as
// corner indices of the polygon.
std::vector<Index3> triangulate(const std::vector<glm::dvec3>& corners) {
  PolygonSoup soup;
  for (const glm::dvec3& p : corners) {
    soup.add_position(p);
    soup.corners.push_back({std::int64_t(soup.positions.size() - 1)});
  }
  soup.end_face();
  const ProxyMesh mesh = assemble_proxy_mesh(soup, "polygon");
  std::vector<Index3> triangles;
  for (const Triangle& t : mesh.triangles) {
    Index3 corner{};
    for (int k = 0; k < 3; ++k)
      corner[k] = std::size_t(std::find(corners.begin(), corners.end(), mesh.positions[t[k]]) - corners.begin());
    triangles.push_back(corner);
  }
  return triangles;
}

double smallest_angle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const auto angle = [](const glm::dvec3& u, const glm::dvec3& v) { return std::acos(glm::dot(glm::normalize(u), glm::normalize(v))); };
  return std::min({angle(b - a, c - a), angle(a - b, c - b), angle(a - c, b - c)});
}

double smallest_angle(const std::vector<glm::dvec3>& p, const std::vector<Index3>& triangles) {
  double smallest = kPi;
  for (const Index3& t : triangles) smallest = std::min(smallest, smallest_angle(p[t[0]], p[t[1]], p[t[2]]));
  return smallest;
}

std::vector<Index3> fan(std::size_t n) {
  std::vector<Index3> triangles;
  for (std::size_t k = 2; k < n; ++k) triangles.push_back({0, k - 1, k});
  return triangles;
}

// Every triangulation of a convex n-gon (Catalan(n − 2) of them).
std::vector<std::vector<Index3>> every_triangulation(std::size_t i, std::size_t j) {
  if (j - i < 2) return {{}};
  std::vector<std::vector<Index3>> all;
  for (std::size_t k = i + 1; k < j; ++k)
    for (const auto& left : every_triangulation(i, k))
      for (const auto& right : every_triangulation(k, j)) {
        std::vector<Index3> t = left;
        t.insert(t.end(), right.begin(), right.end());
        t.push_back({i, k, j});
        all.push_back(t);
      }
  return all;
}

double best_smallest_angle_of_convex(const std::vector<glm::dvec3>& p) {
  double best = 0.0;
  for (const auto& t : every_triangulation(0, p.size() - 1)) best = std::max(best, smallest_angle(p, t));
  return best;
}

// ---- in the plane z = 0 ----
double cross(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}
double signed_area(const std::vector<glm::dvec2>& polygon) {
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const glm::dvec2& a = polygon[i];
    const glm::dvec2& b = polygon[(i + 1) % polygon.size()];
    twice += a.x * b.y - b.x * a.y;
  }
  return twice / 2;
}
bool inside(const std::vector<glm::dvec2>& polygon, const glm::dvec2& q) {  // crossing rule, q off the boundary
  bool in = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const glm::dvec2 &a = polygon[i], &b = polygon[j];
    if ((a.y > q.y) != (b.y > q.y) && q.x < (b.x - a.x) * (q.y - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}
// Two counter-clockwise triangles whose interiors overlap: no edge of either separates them.
bool interiors_overlap(const std::array<glm::dvec2, 3>& s, const std::array<glm::dvec2, 3>& t) {
  const auto separates = [](const std::array<glm::dvec2, 3>& a, const std::array<glm::dvec2, 3>& b) {
    for (int e = 0; e < 3; ++e) {
      bool all_outside = true;
      for (const glm::dvec2& q : b) all_outside = all_outside && cross(a[e], a[(e + 1) % 3], q) <= 1e-12;
      if (all_outside) return true;
    }
    return false;
  };
  return !separates(s, t) && !separates(t, s);
}

// The triangles tile the polygon: each counter-clockwise, inside it, none overlapping another, and
// together as large as the polygon.
void expect_tiling(const std::vector<glm::dvec2>& polygon, const std::vector<Index3>& triangles) {
  ASSERT_EQ(triangles.size(), polygon.size() - 2);
  double area = 0.0;
  std::vector<std::array<glm::dvec2, 3>> plane;
  for (const Index3& t : triangles) {
    const std::array<glm::dvec2, 3> q{polygon[t[0]], polygon[t[1]], polygon[t[2]]};
    const double twice = cross(q[0], q[1], q[2]);
    EXPECT_GT(twice, 0.0) << "triangle " << t[0] << " " << t[1] << " " << t[2] << " is not counter-clockwise";
    area += twice / 2;
    const glm::dvec2 centroid = (q[0] + q[1] + q[2]) / 3.0;
    EXPECT_TRUE(inside(polygon, centroid)) << "triangle " << t[0] << " " << t[1] << " " << t[2] << " lies outside";
    for (int k = 0; k < 3; ++k)  // near each corner, inside the triangle
      EXPECT_TRUE(inside(polygon, q[k] + 0.01 * (centroid - q[k]))) << "triangle " << t[0] << " " << t[1] << " " << t[2];
    plane.push_back(q);
  }
  EXPECT_NEAR(area, signed_area(polygon), 1e-12);
  for (std::size_t a = 0; a < plane.size(); ++a)
    for (std::size_t b = a + 1; b < plane.size(); ++b) EXPECT_FALSE(interiors_overlap(plane[a], plane[b])) << a << " " << b;
}

std::vector<glm::dvec3> lift(const std::vector<glm::dvec2>& polygon) {
  std::vector<glm::dvec3> p;
  for (const glm::dvec2& q : polygon) p.emplace_back(q.x, q.y, 0.0);
  return p;
}

// A regular n-gon: every side subtends π/n at every other corner, so each triangle holding a side
// has that angle and every triangulation's smallest angle is exactly π/n, the fan's too. The known
// optimum is reached, no better and no worse.
TEST(PolygonTriangulation, RegularHeptagonReachesTheKnownOptimum) {
  for (std::size_t n : {5u, 6u, 7u, 12u}) {
    std::vector<glm::dvec3> p;
    for (std::size_t k = 0; k < n; ++k) p.emplace_back(std::cos(2 * kPi * k / n), std::sin(2 * kPi * k / n), 0.0);
    const std::vector<Index3> triangles = triangulate(p);
    ASSERT_EQ(triangles.size(), n - 2);
    EXPECT_NEAR(smallest_angle(p, triangles), kPi / n, 1e-9) << n;
    EXPECT_NEAR(smallest_angle(p, fan(n)), kPi / n, 1e-9) << n;
  }
}

// The regular heptagon stretched 4:1 along x, its first corner at the sharp end: a fan from there
// is all needles (6.53°); the best of the 42 triangulations keeps 16.16°, and the reader finds it.
TEST(PolygonTriangulation, StretchedHeptagonBeatsTheFan) {
  std::vector<glm::dvec3> p;
  for (std::size_t k = 0; k < 7; ++k) p.emplace_back(4 * std::cos(2 * kPi * k / 7), std::sin(2 * kPi * k / 7), 0.0);
  const double best = best_smallest_angle_of_convex(p);
  const double fan_angle = smallest_angle(p, fan(7));
  EXPECT_NEAR(best * 180 / kPi, 16.160, 1e-3);
  EXPECT_NEAR(fan_angle * 180 / kPi, 6.532, 1e-3);
  const std::vector<Index3> triangles = triangulate(p);
  EXPECT_NEAR(smallest_angle(p, triangles), best, 1e-12);
  std::vector<glm::dvec2> plane;
  for (const glm::dvec3& q : p) plane.emplace_back(q.x, q.y);
  expect_tiling(plane, triangles);
}

// Random convex polygons of 5 to 9 corners, in general position in 3D: always the best smallest angle.
TEST(PolygonTriangulation, ConvexPolygonsGetTheBestSmallestAngle) {
  std::uint64_t state = 12345;
  const auto uniform = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) / double(1ull << 53);
  };
  const glm::dvec3 u = glm::normalize(glm::dvec3(1, 2, 3)), v = glm::normalize(glm::cross(u, glm::dvec3(0, 0, 1)));
  for (int trial = 0; trial < 60; ++trial) {
    const std::size_t n = 5 + trial % 5;
    std::vector<double> angles;
    for (std::size_t k = 0; k < n; ++k) angles.push_back(2 * kPi * uniform());
    std::sort(angles.begin(), angles.end());
    const double stretch = 1 + 4 * uniform();
    std::vector<glm::dvec3> p;
    for (double a : angles) p.push_back(glm::dvec3(10, -3, 7) + stretch * std::cos(a) * u + std::sin(a) * v);
    const std::vector<Index3> triangles = triangulate(p);
    ASSERT_EQ(triangles.size(), n - 2);
    EXPECT_NEAR(smallest_angle(p, triangles), best_smallest_angle_of_convex(p), 1e-8) << "trial " << trial;
  }
}

// An L whose first corner is the end of the short arm: a fan from it would lay triangles outside
// the L and wind some backwards.
TEST(PolygonTriangulation, ConcaveLIsCutInsideItself) {
  const std::vector<glm::dvec2> l{{2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}, {2, 0}};
  expect_tiling(l, triangulate(lift(l)));
  double fan_area = 0.0;  // what the fan did: the same corners, but not the same region
  for (const Index3& t : fan(l.size())) fan_area += std::abs(cross(l[t[0]], l[t[1]], l[t[2]])) / 2;
  EXPECT_GT(fan_area, signed_area(l) + 0.5);
}

// A five-pointed star starting at an inner corner, and a comb whose teeth only the right diagonals reach.
TEST(PolygonTriangulation, StarAndCombAreCutInsideThemselves) {
  std::vector<glm::dvec2> star;
  for (int k = 0; k < 10; ++k) {
    const double r = k % 2 == 0 ? 0.38 : 1.0, a = kPi / 2 + kPi * (k + 1) / 5;
    star.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  expect_tiling(star, triangulate(lift(star)));
  std::vector<glm::dvec2> comb{{0, 0}, {9, 0}, {9, 1}};
  for (int tooth = 4; tooth >= 0; --tooth) {
    comb.emplace_back(2 * tooth + 1, 4);
    comb.emplace_back(2 * tooth, 4);
    if (tooth > 0) comb.emplace_back(2 * tooth, 1);
  }
  expect_tiling(comb, triangulate(lift(comb)));
  // Collinear corners (a T-junction on a side, a straight run): no zero-area triangle.
  const std::vector<glm::dvec2> with_straight_corners{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 1}, {1.5, 1}, {0, 1}};
  const std::vector<Index3> triangles = triangulate(lift(with_straight_corners));
  expect_tiling(with_straight_corners, triangles);
  EXPECT_GT(smallest_angle(lift(with_straight_corners), triangles), 0.1);
}

// A larger concave polygon (past the optimal cut's 64 corners) is cut ear by ear, still inside itself.
TEST(PolygonTriangulation, LargeConcavePolygonIsCutEarByEar) {
  std::vector<glm::dvec2> gear;
  for (int k = 0; k < 150; ++k) {
    const double r = k % 2 == 0 ? 1.0 : 0.7, a = 2 * kPi * k / 150;
    gear.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  expect_tiling(gear, triangulate(lift(gear)));
}

// A saddle hexagon (corners alternately 0.3 above and below the plane): cut across its plane, the
// triangles keep its winding (normals on the side of its Newell normal, +z) and the best angle.
TEST(PolygonTriangulation, NonPlanarHexagon) {
  std::vector<glm::dvec3> p;
  for (int k = 0; k < 6; ++k) p.emplace_back(std::cos(kPi * k / 3), std::sin(kPi * k / 3), k % 2 ? 0.3 : -0.3);
  const std::vector<Index3> triangles = triangulate(p);
  ASSERT_EQ(triangles.size(), 4u);
  for (const Index3& t : triangles) EXPECT_GT(glm::cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]).z, 0.0);
  EXPECT_NEAR(smallest_angle(p, triangles), best_smallest_angle_of_convex(p), 1e-12);
  std::vector<std::size_t> used;
  for (const Index3& t : triangles) used.insert(used.end(), t.begin(), t.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  EXPECT_EQ(used.size(), 6u);
}

// A concave quad (a dart) whose shorter diagonal runs outside it: cut along the other one.
TEST(PolygonTriangulation, ConcaveQuadIsCutAlongTheDiagonalInside) {
  const std::vector<glm::dvec2> dart{{0, 5}, {-2, -1}, {0, 0}, {2, -1}};
  expect_tiling(dart, triangulate(lift(dart)));
}

// Files: a 7-gon becomes 5 triangles, emitted together and in file order with the other faces.
TEST(PolygonTriangulation, FilesWithHeptagonsReadIntoTheirTriangles) {
  TempDir dir;
  std::string obj;
  for (int k = 0; k < 7; ++k)
    obj += "v " + std::to_string(4 * std::cos(2 * kPi * k / 7)) + " " + std::to_string(std::sin(2 * kPi * k / 7)) + " 0\n";
  obj += "v 0 0 -3\nf 1 2 3 4 5 6 7\nf 2 1 8\n";
  const ProxyMesh from_obj = read_proxy_mesh(dir.write("h.obj", obj));
  ASSERT_EQ(from_obj.triangles.size(), 6u);
  for (std::size_t t = 0; t < 5; ++t)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(from_obj.corner_position(t, k).z, 0.0);  // the heptagon's first
  EXPECT_EQ(from_obj.corner_position(5, 2), glm::dvec3(0, 0, -3));

  const ProxyMesh from_off = read_proxy_mesh(dir.write("h.off",
      "OFF\n11 3 0\n"
      "4 0 0\n2.49 0.78 0\n-0.89 0.97 0\n-3.6 0.43 0\n-3.6 -0.43 0\n-0.89 -0.97 0\n2.49 -0.78 0\n"
      "0 0 5\n1 0 5\n1 1 5\n0 1 5\n"
      "3 0 1 7\n7 0 1 2 3 4 5 6\n4 7 8 9 10\n"));
  ASSERT_EQ(from_off.triangles.size(), 1u + 5u + 2u);
  for (std::size_t t = 1; t < 6; ++t)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(from_off.corner_position(t, k).z, 0.0);
  EXPECT_EQ(from_off.corner_position(0, 2), glm::dvec3(0, 0, 5));  // triangle 0 is face 0
}

}  // namespace
}  // namespace nano::mesh
