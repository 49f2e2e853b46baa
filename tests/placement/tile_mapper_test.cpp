// Tile mapper vs a double-precision oracle built independently from barycentric interpolation
// (X = Σλᵢ Pᵢ, n = normalize(Σλᵢ nᵢ)), double matrix inverses and glm::dquat rotations.
#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include "shared/tile_mapper.h"
#include "test_util.hpp"

namespace {
using namespace placement_test;
namespace g = nano::gpu;

struct Case {
  glm::vec3 P[3], n[3];
  glm::vec2 t[3];
};

// Double oracle of one triangle.
struct Oracle {
  dvec3 P[3], n[3];
  dvec2 t[3];
  explicit Oracle(const Case& c) {
    for (int i = 0; i < 3; ++i) P[i] = D(c.P[i]), n[i] = D(c.n[i]), t[i] = D(c.t[i]);
  }
  double cross2(dvec2 a, dvec2 b) const { return a.x * b.y - a.y * b.x; }
  dvec3 bary(dvec2 p) const {  // areas ratio (Cramer)
    double area = cross2(t[1] - t[0], t[2] - t[0]);
    double l1 = cross2(p - t[0], t[2] - t[0]) / area;
    double l2 = cross2(t[1] - t[0], p - t[0]) / area;
    return dvec3(1 - l1 - l2, l1, l2);
  }
  dvec3 X(dvec2 p) const {
    dvec3 l = bary(p);
    return l.x * P[0] + l.y * P[1] + l.z * P[2];
  }
  dvec3 normal(dvec2 p) const {
    dvec3 l = bary(p);
    return glm::normalize(l.x * n[0] + l.y * n[1] + l.z * n[2]);
  }
  // Phong tessellation as Boubekeur & Alexa define it: the flat point projected onto each corner's
  // tangent plane, those projections blended by the barycentrics, then by α with the flat point.
  dvec3 X_smooth(dvec2 p, double alpha) const {
    const dvec3 l = bary(p), flat = X(p);
    dvec3 blended(0.0);
    for (int i = 0; i < 3; ++i) {
      const dvec3 m = glm::normalize(n[i]);
      blended += l[i] * (flat - glm::dot(flat - P[i], m) * m);
    }
    return (1 - alpha) * flat + alpha * blended;
  }
  dvec3 face() const { return glm::normalize(glm::cross(P[1] - P[0], P[2] - P[0])); }
  // ∂X/∂u by central difference of the exactly affine X (exact up to rounding).
  dvec3 ju() const { return X(dvec2(1, 0)) - X(dvec2(0, 0)); }
  dvec3 jv() const { return X(dvec2(0, 1)) - X(dvec2(0, 0)); }
  double diameter() const {
    return std::max({glm::length(P[1] - P[0]), glm::length(P[2] - P[0]), glm::length(P[2] - P[1])});
  }
};

Case random_case(Rng& rng, glm::vec3 offset, bool mirrored) {
  for (;;) {
    Case c;
    for (int i = 0; i < 3; ++i) c.P[i] = offset + rng.in_box(-100, 100);
    glm::vec3 f = glm::cross(c.P[1] - c.P[0], c.P[2] - c.P[0]);
    if (glm::length(f) < 2000) continue;  // skip near-degenerate world triangles here
    f = glm::normalize(f);
    for (int i = 0; i < 3; ++i) c.n[i] = glm::normalize(f + 0.3f * rng.unit_vector());
    for (int i = 0; i < 3; ++i) c.t[i] = glm::vec2(float(rng.uniform(0.05, 0.95)), float(rng.uniform(0.05, 0.95)));
    glm::vec2 a = c.t[1] - c.t[0], b = c.t[2] - c.t[0];
    float det = a.x * b.y - a.y * b.x;
    if (std::abs(det) < 0.02f) continue;
    if ((det < 0) != mirrored) std::swap(c.t[1], c.t[2]);
    return c;
  }
}

// A triangle of a sphere of radius 100 with its exact normals, UVs the unit right triangle.
g::TriangleChart sphere_triangle() {
  const glm::vec3 a = glm::normalize(glm::vec3(1, 0.1f, 0.2f)), b = glm::normalize(glm::vec3(0.9f, 0.5f, 0.1f)),
                  c = glm::normalize(glm::vec3(0.95f, 0.2f, 0.55f));
  return g::chart_make(100.f * a, 100.f * b, 100.f * c, glm::vec2(0), glm::vec2(1, 0), glm::vec2(0, 1), a, b, c);
}

g::TriangleChart make(const Case& c) {
  return g::chart_make(c.P[0], c.P[1], c.P[2], c.t[0], c.t[1], c.t[2], c.n[0], c.n[1], c.n[2]);
}

TEST(TileMapper, PositionBarycentricNormalMatchOracleIncludingOverhang) {
  Rng rng(31);
  double worst_x = 0, worst_b = 0, worst_n = 0;
  for (int i = 0; i < 3000; ++i) {
    Case c = random_case(rng, glm::vec3(0), i % 2 == 1);
    Oracle o(c);
    g::TriangleChart ch = make(c);
    ASSERT_TRUE(g::chart_valid(ch));
    EXPECT_EQ(ch.det_e < 0, i % 2 == 1);
    for (int k = 0; k < 3; ++k) {  // corners map to corners
      worst_x = std::max(worst_x, glm::length(D(g::chart_position(ch, c.t[k])) - o.P[k]) / o.diameter());
    }
    for (int k = 0; k < 5; ++k) {
      // points of the UV box widened by 0.1 (tiles hang over edges: negative barycentrics)
      glm::vec2 uv(float(rng.uniform(-0.05, 1.05)), float(rng.uniform(-0.05, 1.05)));
      dvec3 lb = o.bary(D(uv));
      double lmax = std::max({1.0, std::abs(lb.x), std::abs(lb.y), std::abs(lb.z)});
      worst_x = std::max(worst_x, glm::length(D(g::chart_position(ch, uv)) - o.X(D(uv))) / (o.diameter() * lmax));
      worst_b = std::max(worst_b, glm::length(D(g::chart_barycentric(ch, uv)) - lb) / lmax);
      if (std::abs(glm::length(lb.x * o.n[0] + lb.y * o.n[1] + lb.z * o.n[2])) > 0.3)
        worst_n = std::max(worst_n, glm::length(D(g::chart_normal(ch, uv)) - o.normal(D(uv))));
    }
  }
  EXPECT_LT(worst_x, 2e-5);
  EXPECT_LT(worst_b, 2e-5);
  EXPECT_LT(worst_n, 2e-5);
  RecordProperty("max_rel_position_error", std::to_string(worst_x));
  std::printf("tile mapper: max rel X error %.3g, barycentric %.3g, normal %.3g\n", worst_x, worst_b, worst_n);
}

TEST(TileMapper, TileFrameMapsTileSquareOntoUvSquareAndInvertsAnalytically) {
  Rng rng(32);
  double worst_fwd = 0, worst_inv = 0, worst_dir = 0;
  for (int i = 0; i < 3000; ++i) {
    bool mirrored = i % 2 == 1;
    Case c = random_case(rng, glm::vec3(0), mirrored);
    Oracle o(c);
    g::TriangleChart ch = make(c);
    float S = float(rng.uniform(200, 800));   // tile size, Å
    float s = float(rng.uniform(0.02, 0.3));  // tile UV size
    float r = s / S;
    glm::vec2 gg = glm::vec2(float(rng.integer(-2, 8)), float(rng.integer(-2, 8))) * s;
    g::Affine3 m1 = g::chart_tile_frame(ch, gg, r);
    // det M1 has the sign of det E (mirrored chart ⇒ reflection).
    EXPECT_EQ(glm::determinant(glm::dmat3(m1.linear)) < 0, mirrored);
    double scale = o.diameter() + S;
    for (int k = 0; k < 4; ++k) {
      glm::vec3 x(float(rng.uniform(0, S)), float(rng.uniform(0, S)), float(rng.uniform(-60, 60)));
      if (k == 0) x = glm::vec3(S, 0, 0);
      if (k == 1) x = glm::vec3(0, S, 0);
      dvec3 want = o.X(D(gg) + double(r) * dvec2(x.x, x.y)) + double(x.z) * o.face();
      worst_fwd = std::max(worst_fwd, glm::length(D(g::affine_point(m1, x)) - want) / scale);
    }
    // Inverse vs double inverse of the double-built frame.
    glm::dmat3 L(o.ju() * double(r), o.jv() * double(r), o.face());
    glm::dmat3 Li = glm::inverse(L);
    dvec3 X0 = o.X(D(gg));
    glm::vec3 ro = rng.in_box(-300, 300), rd = rng.unit_vector() * float(rng.uniform(0.1, 10));
    glm::vec3 ot, dt;
    g::chart_tile_inverse_ray(ch, gg, r, ro, rd, ot, dt);
    dvec3 want_o = Li * (D(ro) - X0), want_d = Li * D(rd);
    worst_inv = std::max(worst_inv, glm::length(D(ot) - want_o) / (glm::length(want_o) + S));
    worst_dir = std::max(worst_dir, glm::length(D(dt) - want_d) / glm::length(want_d));
    g::Affine3 m1i = g::chart_tile_frame_inverse(ch, gg, r);
    worst_inv = std::max(worst_inv, glm::length(D(g::affine_point(m1i, ro)) - want_o) / (glm::length(want_o) + S));
  }
  EXPECT_LT(worst_fwd, 2e-5);
  EXPECT_LT(worst_inv, 5e-5);
  EXPECT_LT(worst_dir, 5e-5);
  std::printf("tile frame: max rel fwd %.3g, inverse point %.3g, inverse dir %.3g\n", worst_fwd, worst_inv, worst_dir);
}

// The smooth surface copies stand on (chart_smooth_position): Phong tessellation as the oracle
// defines it, with its overhang; the corners stay put; two triangles sharing an edge agree on it
// (no crack between neighbouring triangles' copies); chart_smooth_bulge bounds its lift off the facet;
// on a sphere with exact normals and shape factor 1/2 it lies on the sphere (to second order).
TEST(TileMapper, SmoothSurfaceIsPhongTessellationContinuousAcrossEdges) {
  Rng rng(35);
  double worst = 0;
  for (int i = 0; i < 2000; ++i) {
    Case c = random_case(rng, glm::vec3(0), i % 2 == 1);
    Oracle o(c);
    g::TriangleChart ch = make(c);
    const float alpha = float(rng.uniform(0.0, 1.0));
    for (int k = 0; k < 3; ++k)
      EXPECT_LT(glm::length(D(g::chart_smooth_position(ch, c.t[k], alpha)) - o.P[k]), 1e-4 * o.diameter());
    const double bulge = g::chart_smooth_bulge(ch, alpha);
    float lift_lo, lift_hi;
    g::chart_smooth_lift_range(ch, alpha, lift_lo, lift_hi);
    EXPECT_LE(lift_lo, 0.0f);
    EXPECT_GE(lift_hi, 0.0f);
    EXPECT_LE(std::max(-lift_lo, lift_hi), bulge * (1 + 1e-4) + 1e-3);
    for (int k = 0; k < 5; ++k) {
      glm::vec2 uv(float(rng.uniform(-0.05, 1.05)), float(rng.uniform(-0.05, 1.05)));
      dvec3 lb = o.bary(D(uv));
      double lmax = std::max({1.0, std::abs(lb.x), std::abs(lb.y), std::abs(lb.z)});
      worst = std::max(worst, glm::length(D(g::chart_smooth_position(ch, uv, alpha)) - o.X_smooth(D(uv), alpha)) /
                                  (o.diameter() * lmax * lmax));
      if (lb.x >= 0 && lb.y >= 0 && lb.z >= 0) {
        const dvec3 lift = D(g::chart_smooth_position(ch, uv, alpha)) - o.X(D(uv));
        EXPECT_LE(glm::length(lift), bulge * (1 + 1e-4) + 1e-3);
        // The oracle's lift along its face normal lies within the range.
        const double along = glm::dot(o.X_smooth(D(uv), alpha) - o.X(D(uv)), o.face());
        EXPECT_GE(along, lift_lo - 1e-4 * (bulge + 1.0) - 1e-3);
        EXPECT_LE(along, lift_hi + 1e-4 * (bulge + 1.0) + 1e-3);
      }
    }
    // The same edge P0–P1 in a second triangle with another third corner, UVs and its own order.
    Case other = c;
    other.P[2] = c.P[2] + rng.in_box(-50, 50);
    other.n[2] = rng.unit_vector();
    std::swap(other.P[0], other.P[1]);
    std::swap(other.n[0], other.n[1]);
    other.t[0] = glm::vec2(0.1f, 0.2f), other.t[1] = glm::vec2(0.8f, 0.3f), other.t[2] = glm::vec2(0.4f, 0.9f);
    g::TriangleChart ch2 = make(other);
    const float f = float(rng.uniform(0.0, 1.0));
    const glm::vec2 on_edge = (1 - f) * c.t[0] + f * c.t[1], on_edge2 = (1 - f) * other.t[1] + f * other.t[0];
    EXPECT_LT(glm::length(D(g::chart_smooth_position(ch, on_edge, alpha)) - D(g::chart_smooth_position(ch2, on_edge2, alpha))),
              1e-4 * o.diameter());
  }
  EXPECT_LT(worst, 2e-5);
  const g::TriangleChart sphere = sphere_triangle();
  const glm::vec2 centre(1.f / 3.f, 1.f / 3.f);
  const double flat_gap = 100.0 - glm::length(D(g::chart_position(sphere, centre)));
  // Half of Phong's lift puts the centre back on the sphere to second order (Phong's usual 3/4
  // overshoots it by half the facet's sag).
  const double smooth_gap = std::abs(100.0 - glm::length(D(g::chart_smooth_position(sphere, centre, 0.5f))));
  EXPECT_GT(flat_gap, 1.0);
  EXPECT_LT(smooth_gap, 0.05 * flat_gap);
  EXPECT_EQ(D(g::chart_smooth_position(sphere, centre, 0.f)), D(g::chart_position(sphere, centre)));
}

// The per-tile lift plane: at any point of a tile, the oracle's lift in tile space (through its own
// double M1⁻¹) minus the plane is exactly the curvature term, component by component (the shader's
// boxes hold only that); moving a tile-space ray by the plane moves each of its points by the
// plane's value there and keeps t.
TEST(TileMapper, LiftPlaneLeavesExactlyTheCurvatureTerm) {
  Rng rng(53);
  double worst = 0, worst_ray = 0, largest_plane_share = 0;
  for (int i = 0; i < 2000; ++i) {
    Case c = random_case(rng, glm::vec3(0), i % 2 == 1);
    Oracle o(c);
    const g::TriangleChart ch = make(c);
    const float alpha = float(rng.uniform(0.0, 1.0));
    const float S = float(rng.uniform(20.0, 200.0));
    const float s_over_S = float(rng.uniform(0.05, 0.4)) / S;
    const glm::mat3 k = g::chart_smooth_lift_coefficients(ch, alpha);
    const glm::mat3 directions = g::chart_lift_directions(ch, s_over_S);
    const glm::vec2 g0(float(rng.uniform(-0.2, 1.0)), float(rng.uniform(-0.2, 1.0)));
    const glm::vec2 centre(0.5f * S);
    const g::LiftPlane plane = g::chart_smooth_lift_plane(ch, k, directions, g0, s_over_S, centre);
    const glm::mat3 h = g::chart_smooth_lift_curvature(ch, k, directions, s_over_S);
    const glm::dmat3 to_tile = glm::inverse(glm::dmat3(o.ju() * double(s_over_S), o.jv() * double(s_over_S), o.face()));
    const double bulge = g::chart_smooth_bulge(ch, alpha) + 1.0;
    for (int n = 0; n < 8; ++n) {
      const dvec2 delta(rng.uniform(-0.5, 0.5) * S, rng.uniform(-0.5, 0.5) * S);
      const dvec2 uv = D(g0) + double(s_over_S) * (D(centre) + delta);
      const dvec3 l = o.bary(uv);
      const double lmax = std::max({1.0, std::abs(l.x), std::abs(l.y), std::abs(l.z)});
      const dvec3 lift = to_tile * (o.X_smooth(uv, alpha) - o.X(uv));
      const dvec3 on_plane = D(plane.value) + D(plane.dx) * delta.x + D(plane.dy) * delta.y;
      dvec3 curvature;
      for (int r = 0; r < 3; ++r)
        curvature[r] = delta.x * delta.x * h[r].x + 2 * delta.x * delta.y * h[r].y + delta.y * delta.y * h[r].z;
      const double scale = bulge * lmax * lmax * (1 + glm::length(to_tile[0]) + glm::length(to_tile[1]));
      worst = std::max(worst, glm::length(lift - on_plane - curvature) / scale);
      largest_plane_share = std::max(largest_plane_share, std::abs(on_plane.z) / (std::abs(lift.z) + 1e-9));
    }
    glm::vec3 ot = rng.in_box(-300, 300), dt = rng.in_box(-1, 1), o2 = ot, d2 = dt;
    g::chart_lift_shear_ray(plane, centre, o2, d2);
    for (const double t : {0.0, 1.7, 250.0}) {
      const dvec3 p = D(ot) + t * D(dt), p2 = D(o2) + t * D(d2);
      const dvec3 moved = D(plane.value) + D(plane.dx) * (p.x - centre.x) + D(plane.dy) * (p.y - centre.y);
      const double scale = glm::length(p) * (1 + glm::length(D(plane.dx)) + glm::length(D(plane.dy))) +
                           glm::length(D(plane.value)) + bulge;
      worst_ray = std::max(worst_ray, glm::length(p2 - (p - moved)) / scale);
    }
  }
  EXPECT_LT(worst, 1e-5);
  EXPECT_LT(worst_ray, 1e-5);
  EXPECT_GT(largest_plane_share, 0.5);  // the plane carries the lift (a zero plane would pass the rest)
  // On a triangle of a sphere of radius 100 seen through tiles a tenth of its size, the curvature term
  // is a small part of the whole lift (what the boxes no longer hold).
  const g::TriangleChart sphere = sphere_triangle();
  float lift_lo, lift_hi;
  g::chart_smooth_lift_range(sphere, 0.5f, lift_lo, lift_hi);
  const float S = 10.f, s_over_S = 0.1f / S;
  const glm::mat3 h = g::chart_smooth_lift_curvature(sphere, g::chart_smooth_lift_coefficients(sphere, 0.5f),
                                                     g::chart_lift_directions(sphere, s_over_S), s_over_S);
  double term = 0;
  for (int r = 0; r < 3; ++r) term += (std::abs(h[r].x) + 2 * std::abs(h[r].y) + std::abs(h[r].z)) * (S / 2) * (S / 2);
  EXPECT_GT(lift_hi - lift_lo, 1.0);
  EXPECT_LT(term, 0.05 * (lift_hi - lift_lo));
}

TEST(TileMapper, MembraneMoleculeTransformAndRayMatchOracle) {
  Rng rng(33);
  double worst_p = 0, worst_r = 0, worst_ray = 0;
  for (int i = 0; i < 3000; ++i) {
    Case c = random_case(rng, glm::vec3(0), i % 3 == 0);
    Oracle o(c);
    g::TriangleChart ch = make(c);
    float S = 500, s = float(rng.uniform(0.02, 0.3)), r = s / S;
    glm::vec2 gg = glm::vec2(float(rng.integer(0, 5)), float(rng.integer(0, 5))) * s;
    glm::vec3 pos(float(rng.uniform(0, S)), float(rng.uniform(0, S)), float(rng.uniform(-50, 50)));
    glm::vec3 axis = rng.unit_vector();
    float ang = float(rng.uniform(-3.14, 3.14));
    glm::vec4 q = g::quat_from_axis_angle(axis, ang);
    glm::vec2 uvm;
    const float smooth = i % 2 == 0 ? 0.f : float(rng.uniform(0.0, 1.0));
    g::Affine3 m = g::chart_membrane_molecule(ch, gg, r, smooth, pos, q, uvm);
    dvec2 uv_o = D(gg) + double(r) * dvec2(pos.x, pos.y);
    ASSERT_LT(glm::length(D(uvm) - uv_o), 1e-6);
    dvec3 n = o.normal(D(uvm));
    dvec3 want_p = o.X_smooth(D(uvm), smooth) + double(pos.z) * n;
    // The smooth surface is quadratic in the barycentrics: its float error grows with their square
    // far outside the triangle (owned copies lie inside it).
    const dvec3 lb = o.bary(D(uvm));
    const double lmax = smooth > 0 ? std::max({1.0, std::abs(lb.x), std::abs(lb.y), std::abs(lb.z)}) : 1.0;
    worst_p = std::max(worst_p, glm::length(D(m.translation) - want_p) / ((o.diameter() + 50) * lmax * lmax));
    dvec3 ju = o.ju();
    dvec3 fx = glm::normalize(ju - glm::dot(ju, n) * n);
    dvec3 fy = glm::cross(n, fx);
    // The frame turns by the rotation of the polar decomposition G = R·P of the in-plane map
    // G = [fx fy]ᵀ·[Ju Jv] (when det G > 0), found here by Newton's iteration R ← (R + R⁻ᵀ)/2.
    glm::dmat2 G(glm::dot(fx, ju), glm::dot(fy, ju), glm::dot(fx, o.jv()), glm::dot(fy, o.jv()));
    if (glm::determinant(G) > 0) {
      glm::dmat2 R = G;
      for (int it = 0; it < 60; ++it) R = 0.5 * (R + glm::transpose(glm::inverse(R)));
      const dvec2 c0 = R[0];  // image of (1, 0): (cos θ, sin θ)
      const dvec3 tx = c0.x * fx + c0.y * fy;
      fy = c0.x * fy - c0.y * fx;
      fx = tx;
    }
    glm::dmat3 frame(fx, fy, n);
    glm::dmat3 rq = glm::mat3_cast(glm::angleAxis(double(ang), glm::normalize(D(axis))));
    glm::dmat3 want_r = frame * rq;
    for (int col = 0; col < 3; ++col) worst_r = std::max(worst_r, glm::length(dvec3(m.linear[col]) - want_r[col]));
    ASSERT_GT(glm::determinant(glm::dmat3(m.linear)), 0.999);  // proper rotation even when mirrored
    // Rays: world point at t maps to the local point at the same t.
    glm::vec3 ro = rng.in_box(-300, 300), rd = rng.unit_vector() * float(rng.uniform(0.1, 10));
    glm::vec3 ol, dl;
    g::molecule_inverse_ray(m, ro, rd, ol, dl);
    for (double t : {0.0, 3.0, 40.0}) {
      dvec3 wp = D(ro) + t * D(rd);
      dvec3 want_l = glm::transpose(want_r) * (wp - want_p);
      dvec3 got_l = D(ol) + t * D(dl);
      worst_ray = std::max(worst_ray, glm::length(got_l - want_l) / (glm::length(wp - want_p) + 1.0));
    }
  }
  EXPECT_LT(worst_p, 2e-5);
  EXPECT_LT(worst_r, 2e-5);
  EXPECT_LT(worst_ray, 5e-5);
  std::printf("membrane M2: max rel position %.3g, rotation %.3g, local ray %.3g\n", worst_p, worst_r, worst_ray);
}

TEST(TileMapper, SolubleMoleculeInCoreBox) {
  Rng rng(34);
  double worst = 0;
  for (int i = 0; i < 2000; ++i) {
    glm::vec3 gmin = rng.in_box(-1000, 1000), box(float(rng.uniform(100, 400)));
    glm::ivec3 ijk(rng.integer(0, 30), rng.integer(0, 30), rng.integer(0, 30));
    glm::vec3 pos = rng.in_box(0, 100);
    glm::vec3 axis = rng.unit_vector();
    float ang = float(rng.uniform(-3.14, 3.14));
    g::Affine3 inst;
    inst.linear = glm::mat3(2.0f) * g::quat_to_mat3(g::quat_from_axis_angle(rng.unit_vector(), 0.7f));
    inst.translation = rng.in_box(-500, 500);
    g::Affine3 m = g::affine_compose(inst, g::core_soluble_molecule(g::core_box_min(gmin, box, ijk), pos,
                                                                    g::quat_from_axis_angle(axis, ang)));
    dvec3 local = D(rng.in_box(-20, 20));
    dvec3 box_min = D(gmin) + dvec3(ijk) * D(box);
    dvec3 want = glm::dmat3(inst.linear) * (box_min + D(pos) + glm::mat3_cast(glm::angleAxis(double(ang), glm::normalize(D(axis)))) * local) +
                 D(inst.translation);
    dvec3 got = D(g::affine_point(m, glm::vec3(local)));
    worst = std::max(worst, glm::length(got - want) / glm::length(want));
    // and back with the general inverse ray
    glm::vec3 ol, dl;
    g::affine_inverse_ray(m, glm::vec3(want), glm::vec3(1, 2, 3), ol, dl);
    worst = std::max(worst, glm::length(D(ol) - local) / glm::length(want));
  }
  EXPECT_LT(worst, 2e-6);
}

TEST(TileMapper, ReplicationAreaCoversEveryTouchedTile) {
  Rng rng(35);
  int max_excess = 0;
  for (int i = 0; i < 20000; ++i) {
    float s = float(rng.uniform(0.003, 0.25));
    glm::vec2 t[3];
    for (auto& x : t) x = glm::vec2(float(rng.uniform(0, 1)), float(rng.uniform(0, 1)));
    if (i % 4 == 0)  // tiles starting exactly on tile boundaries
      for (auto& x : t) x = glm::vec2(float(rng.integer(0, 10)) * s, float(rng.integer(0, 10)) * s);
    glm::vec2 lo = glm::min(t[0], glm::min(t[1], t[2])), hi = glm::max(t[0], glm::max(t[1], t[2]));
    glm::ivec2 org = g::replication_origin(lo, s), ext = g::replication_extent(lo, hi, s);
    glm::ivec2 bound = g::replication_extent_bound(lo, hi, s);
    for (int a = 0; a < 2; ++a) {
      // brute force in double: cells k whose half-open UV interval [k s, (k+1) s) meets [lo, hi]
      double dl = lo[a], dh = hi[a], ds = s;
      for (int k = int(std::floor(dl / ds)) - 2; k <= int(std::floor(dh / ds)) + 2; ++k) {
        bool touches = (k + 1) * ds > dl && k * ds <= dh;
        bool inside = k >= org[a] && k < org[a] + ext[a];
        if (touches) {
          ASSERT_TRUE(inside) << "tile " << k << " of axis " << a << " missing; lo " << dl << " hi " << dh << " s " << ds << " org " << org[a] << " ext " << ext[a] << " case " << i;
        }
      }
      ASSERT_LE(ext[a], bound[a]);
      max_excess = std::max(max_excess, ext[a] - int(std::ceil((dh - dl) / ds)));
      // the UV origin of slot 0 is at or below uv_min
      ASSERT_LE(g::replication_tile_uv(g::replication_tile_index(org, glm::ivec2(0)), s)[a], lo[a]);
    }
  }
  EXPECT_LE(max_excess, 2);  // +1 of ALGORITHMS.md, +1 more only when an edge is within the slack of a boundary
}
}  // namespace
