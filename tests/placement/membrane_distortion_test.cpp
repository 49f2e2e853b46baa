// The renderer's membrane molecule boxes (runtime/placement/membrane_distortion.hpp) against the
// placement they bound: copies placed by chart_membrane_molecule (what the shader and the CPU oracle
// draw) on facets of a sphere, their atoms carried into the slot's tile space by a double-precision
// inverse of M1 and sheared by the tile's lift plane as the shader shears its rays, must lie inside
// the boxes copy_boxes gives; curvature_range against its quadratic evaluated at the corners of the
// curvature box (it is linear in each curvature) and at random points inside it.
#include <gtest/gtest.h>

#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "runtime/placement/membrane_distortion.hpp"
#include "shared/tile_mapper.h"
#include "test_util.hpp"

namespace {
using namespace placement_test;
namespace g = nano::gpu;
namespace pl = nano::placement;
using glm::dmat3;

// A triangle of a sphere of radius `radius` around the north pole spanning about `angle` radians, with
// the sphere's normals at its corners and UVs the tangent-plane coordinates over `k` Å per UV unit.
pl::MembraneTriangleCorners sphere_facet(double radius, double angle, double k, double turn) {
  pl::MembraneTriangleCorners t;
  for (int i = 0; i < 3; ++i) {
    const double a = turn + i * 2.0943951023931953;  // 120° apart
    const dvec3 dir = glm::normalize(dvec3(std::sin(angle) * std::cos(a), std::sin(angle) * std::sin(a), std::cos(angle)));
    t.position[i] = glm::vec3(dir * radius);
    t.normal[i] = glm::vec3(dir);
    t.uv[i] = glm::vec2(float(dir.x * radius / k), float(dir.y * radius / k));
  }
  return t;
}

struct Copy {
  dvec3 pos;                   // tile-space position
  glm::vec4 rotation;          // unit quaternion
  std::vector<glm::vec4> atoms;  // molecule-space centre and radius
};

Copy random_copy(Rng& rng, double size) {
  Copy c;
  c.pos = dvec3(rng.uniform(0, size), rng.uniform(0, size), rng.uniform(-40, 40));
  const glm::vec3 axis = rng.unit_vector();
  const double half_angle = rng.uniform(0, 3.14159);
  c.rotation = glm::vec4(axis * float(std::sin(half_angle)), float(std::cos(half_angle)));
  for (int a = 0; a < 12; ++a) c.atoms.push_back(glm::vec4(rng.in_box(-12, 12), float(rng.uniform(1, 2.5))));
  return c;
}

// The M1-placed extent of a copy's atoms about its origin (c ± h) and its bounding radius, in double.
void placed_extent(const Copy& copy, dvec3& c, dvec3& h, double& r) {
  const glm::dquat q(copy.rotation.w, copy.rotation.x, copy.rotation.y, copy.rotation.z);
  dvec3 lo(INFINITY), hi(-INFINITY);
  r = 0;
  for (const glm::vec4& a : copy.atoms) {
    const dvec3 p = glm::mat3_cast(glm::normalize(q)) * dvec3(glm::vec3(a));
    lo = glm::min(lo, p - double(a.w)), hi = glm::max(hi, p + double(a.w));
    r = std::max(r, glm::length(dvec3(glm::vec3(a))) + a.w);
  }
  c = (lo + hi) * 0.5, h = (hi - lo) * 0.5;
}

bool inside(const dvec3& p, double radius, const dvec3& lo, const dvec3& hi) {
  return glm::all(glm::greaterThanEqual(p - radius, lo)) && glm::all(glm::lessThanEqual(p + radius, hi));
}

struct Tally {
  int copies = 0, sheared = 0;
};

// Every copy of `copies` that triangle `corners` owns (its UV inside the triangle), placed in each
// tile that puts it there, inside its boxes.
Tally check_triangle(const pl::MembraneTriangleCorners& corners, const pl::MembraneTiling& tiling, double size, Rng& rng) {
  Tally tally;
  const std::optional<pl::MembraneDistortion> d = pl::triangle_distortion(corners, tiling);
  EXPECT_TRUE(d.has_value());
  if (!d) return tally;
  const g::TriangleChart chart = g::chart_make(corners.position[0], corners.position[1], corners.position[2], corners.uv[0],
                                               corners.uv[1], corners.uv[2], corners.normal[0], corners.normal[1], corners.normal[2]);
  const dmat3 m1(dvec3(chart.ju) * double(tiling.s_over_S), dvec3(chart.jv) * double(tiling.s_over_S), dvec3(chart.face_normal));
  const dmat3 to_tile = glm::inverse(m1);
  // The shader shears by the smooth lift's plane, or by none on a triangle the host left unsheared.
  const glm::mat3 k = g::chart_smooth_lift_coefficients(chart, d->has_unsheared() ? 0.f : tiling.smoothness);
  const glm::mat3 directions = g::chart_lift_directions(chart, tiling.s_over_S);
  const glm::vec2 uv_lo = glm::min(corners.uv[0], glm::min(corners.uv[1], corners.uv[2]));
  const glm::vec2 uv_hi = glm::max(corners.uv[0], glm::max(corners.uv[1], corners.uv[2]));
  const glm::ivec2 first = g::replication_origin(uv_lo, tiling.tile_uv);
  const glm::ivec2 extent = g::replication_extent(uv_lo, uv_hi, tiling.tile_uv);
  for (int trial = 0; trial < 4000; ++trial) {
    const glm::ivec2 cell = first + glm::ivec2(rng.integer(0, extent.x - 1), rng.integer(0, extent.y - 1));
    const glm::vec2 tile = g::replication_tile_uv(cell, tiling.tile_uv);
    const Copy copy = random_copy(rng, size);
    glm::vec2 uv_m;
    const g::Affine3 placed = g::chart_membrane_molecule(chart, tile, tiling.s_over_S, tiling.smoothness, glm::vec3(copy.pos),
                                                         copy.rotation, uv_m);
    const glm::vec3 bary = g::chart_barycentric(chart, uv_m);
    if (bary.x < 0 || bary.y < 0 || bary.z < 0) continue;  // another triangle owns it
    dvec3 c, h;
    double r;
    placed_extent(copy, c, h, r);
    const pl::CopyBoxes boxes = pl::copy_boxes(copy.pos, c, h, r, *d, tiling.half);
    const g::LiftPlane plane = g::chart_smooth_lift_plane(chart, k, directions, tile, tiling.s_over_S, glm::vec2(tiling.half));
    const dvec3 origin = dvec3(g::chart_position(chart, tile));
    for (const glm::vec4& a : copy.atoms) {
      const dvec3 world = dvec3(placed.translation) + dmat3(placed.linear) * dvec3(glm::vec3(a));
      const dvec3 p = to_tile * (world - origin);
      const dvec3 sheared = p - (dvec3(plane.value) + dvec3(plane.dx) * (p.x - tiling.half) + dvec3(plane.dy) * (p.y - tiling.half));
      EXPECT_TRUE(inside(sheared, a.w, boxes.lo, boxes.hi)) << "copy at " << copy.pos.x << ", " << copy.pos.y << ", " << copy.pos.z;
      EXPECT_TRUE(inside(p, a.w, boxes.reach_lo, boxes.reach_hi)) << "copy at " << copy.pos.x << ", " << copy.pos.y << ", " << copy.pos.z;
    }
    ++tally.copies;
  }
  tally.sheared = d->has_sheared() ? 1 : 0;
  return tally;
}

// 150 Å Wang squares on 10 Å per UV unit, the baker's shape factor 1/2.
constexpr double kSquare = 150, kScale = 10;
const pl::MembraneTiling kTiling{float(kSquare / kScale), float(1 / kScale), float(kSquare / 2), 0.5f};

TEST(MembraneDistortion, CoarseFacetBoxesHoldTheirCopies) {
  // A red-cell-like facet: 300 Å across on a 900 Å sphere, lifted tens of Å off its plane.
  Rng rng(7);
  const Tally t = check_triangle(sphere_facet(900, 0.2, kScale, 0.3), kTiling, kSquare, rng);
  EXPECT_GT(t.copies, 200);
  EXPECT_EQ(t.sheared, 1);  // the plane's shear is the tighter bound there
}

TEST(MembraneDistortion, FineFacetBoxesHoldTheirCopies) {
  Rng rng(11);
  const Tally t = check_triangle(sphere_facet(600, 0.05, kScale, 1.1), kTiling, kSquare, rng);
  EXPECT_GT(t.copies, 30);
}

TEST(MembraneDistortion, StretchedChartBoxesHoldTheirCopies) {
  // UVs at 6 Å per unit over a 10 Å tiling: the chart stretches copies by 10/6 across.
  pl::MembraneTriangleCorners corners = sphere_facet(700, 0.15, 6, 2.0);
  Rng rng(13);
  const Tally t = check_triangle(corners, kTiling, kSquare, rng);
  EXPECT_GT(t.copies, 100);
}

TEST(MembraneDistortion, DegenerateTriangleHasNoDistortion) {
  pl::MembraneTriangleCorners corners = sphere_facet(900, 0.2, kScale, 0.3);
  corners.uv[2] = corners.uv[1];
  EXPECT_FALSE(pl::triangle_distortion(corners, kTiling).has_value());
}

TEST(MembraneDistortion, CurvatureRangeIsTheQuadraticsExtremes) {
  Rng rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    const dvec3 a(rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3));
    const dvec3 b(rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3));
    const dvec3 lo = glm::min(a, b), hi = glm::max(a, b);
    const dvec2 delta(rng.uniform(-100, 100), rng.uniform(-100, 100));
    const auto quadratic = [&](const dvec3& h) {
      return delta.x * delta.x * h.x + 2 * delta.x * delta.y * h.y + delta.y * delta.y * h.z;
    };
    double least = INFINITY, most = -INFINITY;
    for (int corner = 0; corner < 8; ++corner) {
      const dvec3 h((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
      least = std::min(least, quadratic(h)), most = std::max(most, quadratic(h));
    }
    const auto [range_lo, range_hi] = pl::curvature_range(lo, hi, delta);
    EXPECT_NEAR(range_lo, least, 1e-12 + 1e-12 * std::abs(least));
    EXPECT_NEAR(range_hi, most, 1e-12 + 1e-12 * std::abs(most));
    for (int k = 0; k < 10; ++k) {
      const dvec3 h = lo + (hi - lo) * dvec3(rng.uniform(), rng.uniform(), rng.uniform());
      EXPECT_GE(quadratic(h), range_lo - 1e-12);
      EXPECT_LE(quadratic(h), range_hi + 1e-12);
    }
  }
}

TEST(MembraneDistortion, ClassesSplitAtTheirSharesAndBoundTheirTriangles) {
  std::vector<std::optional<pl::MembraneDistortion>> per;
  for (int i = 0; i < 8; ++i) per.push_back(pl::triangle_distortion(sphere_facet(900 - 80 * i, 0.2, kScale, 0.4 * i), kTiling));
  per.push_back(std::nullopt);  // a triangle owning nothing stays in class 0 and widens nothing
  const pl::DistortionClasses classes = pl::distortion_classes(per, kTiling.half);
  ASSERT_EQ(classes.of_triangle.size(), per.size());
  int in_last = 0;
  for (std::size_t k = 0; k < per.size(); ++k) {
    in_last += classes.of_triangle[k] == pl::kDistortionClasses - 1;
    if (!per[k]) continue;
    const pl::MembraneDistortion& bound = *classes.bound[classes.of_triangle[k]];
    EXPECT_GE(bound.sigma, per[k]->sigma);
    EXPECT_GE(bound.delta, per[k]->delta);
    EXPECT_GE(bound.bulge, per[k]->bulge);
    EXPECT_LE(bound.lift_lo, per[k]->lift_lo);
    EXPECT_GE(bound.lift_hi, per[k]->lift_hi);
  }
  EXPECT_EQ(in_last, 2);  // the worst quarter of the eight that own copies
  EXPECT_EQ(classes.of_triangle.back(), 0);
}

}  // namespace
