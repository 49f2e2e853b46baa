#include "runtime/placement/membrane_distortion.hpp"

#include <algorithm>
#include <tuple>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "common/singular_value.hpp"
#include "shared/ownership.h"
#include "shared/tile_mapper.h"

namespace nano::placement {

using glm::dmat3;
using glm::dvec2;
using glm::dvec3;
using glm::vec3;

void widen_to(std::optional<MembraneDistortion>& into, const MembraneDistortion& o) {
  MembraneDistortion& d = into ? *into : into.emplace(o);
  d.sigma = std::max(d.sigma, o.sigma), d.delta = std::max(d.delta, o.delta), d.bulge = std::max(d.bulge, o.bulge);
  d.lift_lo = std::min(d.lift_lo, o.lift_lo), d.lift_hi = std::max(d.lift_hi, o.lift_hi);
  for (int col = 0; col < 3; ++col) d.e[col] = glm::max(d.e[col], o.e[col]);
  for (int r = 0; r < 3; ++r)
    d.curvature_lo[r] = glm::min(d.curvature_lo[r], o.curvature_lo[r]), d.curvature_hi[r] = glm::max(d.curvature_hi[r], o.curvature_hi[r]);
  d.slope_x = glm::max(d.slope_x, o.slope_x), d.slope_y = glm::max(d.slope_y, o.slope_y);
  d.unsheared_lo = std::min(d.unsheared_lo, o.unsheared_lo), d.unsheared_hi = std::max(d.unsheared_hi, o.unsheared_hi);
  d.plane_error = std::max(d.plane_error, o.plane_error);
}

std::pair<double, double> curvature_range(const dvec3& lo, const dvec3& hi, const dvec2& delta) {
  const dvec3 w(delta.x * delta.x, 2 * delta.x * delta.y, delta.y * delta.y);
  double out_lo = 0, out_hi = 0;
  for (int k = 0; k < 3; ++k) {
    out_lo += std::min(w[k] * lo[k], w[k] * hi[k]);
    out_hi += std::max(w[k] * lo[k], w[k] * hi[k]);
  }
  return {out_lo, out_hi};
}

std::optional<MembraneDistortion> triangle_distortion(const MembraneTriangleCorners& corners, const MembraneTiling& tiling) {
  const float s_over_S = tiling.s_over_S;
  constexpr int kSteps = 4;
  MembraneDistortion d;
  const glm::vec2 t0 = corners.uv[0], t1 = corners.uv[1], t2 = corners.uv[2];
  if (gpu::own_edge_inner_q(gpu::own_quantize(t0), gpu::own_quantize(t1), gpu::own_quantize(t2)) == 0) return std::nullopt;
  const vec3 n0 = corners.normal[0], n1 = corners.normal[1], n2 = corners.normal[2];
  const gpu::TriangleChart chart =
      gpu::chart_make(corners.position[0], corners.position[1], corners.position[2], t0, t1, t2, n0, n1, n2);
  if (!gpu::chart_valid(chart)) return std::nullopt;  // owns nothing the oracle would accept either
  const dmat3 m1(dvec3(chart.ju) * double(s_over_S), dvec3(chart.jv) * double(s_over_S), dvec3(chart.face_normal));
  const dmat3 l = glm::inverse(m1);
  d.sigma = largest_singular_value(l);
  for (const vec3& n : {n0, n1, n2})
    d.delta = std::max(d.delta, glm::length(glm::normalize(dvec3(n)) - dvec3(chart.face_normal)));
  d.bulge = double(gpu::chart_smooth_bulge(chart, tiling.smoothness));
  float lift_lo, lift_hi;  // a convex stretch of surface lifts only outward: the box grows on one side
  gpu::chart_smooth_lift_range(chart, tiling.smoothness, lift_lo, lift_hi);
  d.lift_lo = lift_lo, d.lift_hi = lift_hi;
  for (int i = 0; i <= kSteps; ++i)
    for (int j = 0; i + j <= kSteps; ++j) {
      const glm::vec2 uv = t0 + (t1 - t0) * (float(i) / kSteps) + (t2 - t0) * (float(j) / kSteps);
      glm::vec2 uv_m;
      const gpu::Affine3 placed =
          gpu::chart_membrane_molecule(chart, uv, s_over_S, tiling.smoothness, vec3(0.f), glm::vec4(0, 0, 0, 1), uv_m);
      const dmat3 tm = l * dmat3(placed.linear);
      for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row)
          d.e[col][row] = std::max(d.e[col][row], std::abs(tm[col][row] - (col == row ? 1.0 : 0.0)));
    }
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row) d.e[col][row] = d.e[col][row] * 1.2 + 0.02;
  // The lift plane: its slopes are affine in UV, so their largest |value| over the tiles the shader
  // takes planes of (centres within the triangle's UV box widened by a tile) is at a corner of that
  // box; so is the largest |barycentric|, which sets the float plane's rounding.
  const glm::mat3 k = gpu::chart_smooth_lift_coefficients(chart, tiling.smoothness);
  const glm::mat3 directions = gpu::chart_lift_directions(chart, s_over_S);
  const double tile = tiling.tile_uv;
  const dvec2 uv_lo = dvec2(glm::min(t0, glm::min(t1, t2))) - tile, uv_hi = dvec2(glm::max(t0, glm::max(t1, t2))) + tile;
  double l_max = 1, lift_scale = 0;
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 3; ++row) lift_scale = std::max(lift_scale, std::abs(double(k[col][row])));
  dvec3 slope_x(0.0), slope_y(0.0);
  for (const dvec2 corner : {uv_lo, dvec2(uv_hi.x, uv_lo.y), dvec2(uv_lo.x, uv_hi.y), uv_hi}) {
    const gpu::LiftPlane plane = gpu::chart_smooth_lift_plane(chart, k, directions, glm::vec2(corner), s_over_S, glm::vec2(0.f));
    slope_x = glm::max(slope_x, glm::abs(dvec3(plane.dx))), slope_y = glm::max(slope_y, glm::abs(dvec3(plane.dy)));
    const dvec3 bary(gpu::chart_barycentric(chart, glm::vec2(corner)));
    l_max = std::max({l_max, std::abs(bary.x), std::abs(bary.y), std::abs(bary.z)});
  }
  slope_x = slope_x * (1 + 1e-3) + 1e-6, slope_y = slope_y * (1 + 1e-3) + 1e-6;
  const dmat3 curvature(gpu::chart_smooth_lift_curvature(chart, k, directions, s_over_S));
  const double half = tiling.half;
  // Sheared, a copy's box grows by its curvature term (at most |h|₁·half² over the tile) and the
  // slope across its width (a lipid's ~15 Å each way); unsheared, by the whole lift: its range
  // along the normal and σ·δ·bulge across.
  double sheared_growth = 0;
  for (int r = 0; r < 3; ++r)
    sheared_growth += 2 * (std::abs(curvature[r].x) + 2 * std::abs(curvature[r].y) + std::abs(curvature[r].z)) * half * half +
                      2 * 15.0 * (slope_x[r] + slope_y[r]);
  if (sheared_growth < d.lift_hi - d.lift_lo + 4 * d.sigma * d.delta * d.bulge) {
    for (int r = 0; r < 3; ++r) {
      const dvec3 margin = glm::abs(curvature[r]) * 1e-4 + 1e-9;
      d.curvature_lo[r] = curvature[r] - margin, d.curvature_hi[r] = curvature[r] + margin;
    }
    d.slope_x = slope_x, d.slope_y = slope_y;
    d.plane_error = 1e-5 * (lift_scale * d.sigma * 3 * l_max * l_max + std::max({slope_x.x + slope_y.x, slope_x.y + slope_y.y, slope_x.z + slope_y.z}) * half * 4);
  } else {
    d.unsheared_lo = d.lift_lo, d.unsheared_hi = d.lift_hi;
  }
  return d;
}

DistortionClasses distortion_classes(std::span<const std::optional<MembraneDistortion>> per, double half) {
  const std::size_t count = per.size();
  DistortionClasses out;
  out.of_triangle.assign(count, 0);
  out.unsheared.assign(count, false);
  std::vector<std::pair<double, std::uint32_t>> ranked;  // (size of a typical lipid's box, local triangle)
  for (std::uint32_t k = 0; k < count; ++k) {
    if (!per[k]) continue;
    out.unsheared[k] = per[k]->has_unsheared();
    // A lipid standing 20 Å off the surface at a tile corner (the curvature term's worst place).
    const CopyBoxes typical = copy_boxes(dvec3(0, 0, 20), dvec3(0.0), dvec3(8, 8, 12), 15, *per[k], half);
    const dvec3 size = typical.hi - typical.lo;
    ranked.push_back({size.x + size.y + size.z, k});
  }
  std::sort(ranked.begin(), ranked.end());
  std::uint32_t cls = 0;
  for (std::size_t r = 0; r < ranked.size(); ++r) {
    while (double(r) >= kClassShare[cls] * double(ranked.size()) && cls + 1 < kDistortionClasses) ++cls;
    const std::uint32_t k = ranked[r].second;
    out.of_triangle[k] = std::uint8_t(cls);
    widen_to(out.bound[cls], *per[k]);
  }
  return out;
}

CopyBoxes copy_boxes(const dvec3& pos, const dvec3& c, const dvec3& h, double r, const MembraneDistortion& d, double half) {
  // δ grows by 1e-3 for the rounding of the normalised interpolation; the pad covers the float
  // tile-space ray (≈ 1e-6 of the distance to the tile) of any camera within 10^5 Å.
  const double sigma = d.sigma * (1 + 1e-4), delta = d.delta + 1e-3, pad = 0.1;
  // Where the true centre lies off M1's: z·(n − N) + (X_smooth − X_flat). L keeps a world
  // vector's component along N as tile z and maps its tangential part, at most σ-stretched,
  // to tile x, y. Along N: |z|·(1 − cos θ) = |z|·|n − N|²/2 ≤ |z|·δ²/2, and the lift ≤ b;
  // tangentially: |z|·sin θ ≤ |z|·δ, and the lift, a combination of corner normals each
  // within δ of N, ≤ b·δ.
  // Along N the parts have known signs: z·(n·N − 1) lies between 0 and −z·δ²/2, and the lift
  // between d.lift_lo and d.lift_hi (floats: widened by 1e-4 of the bulge and 1e-3 Å).
  const double bulge = d.bulge * (1 + 1e-4), slack = 1e-4 * bulge + 1e-3;
  const double turn_xy = sigma * delta * std::abs(pos.z), lift_xy = sigma * delta * bulge;
  const double turn_z = pos.z * delta * delta / 2;
  // Two bounds of the same copy, both containing it: its own atoms' box widened by the chart's turn
  // and stretch, and the sphere of its bounding radius (stretched by up to σ in tile x, y, not in
  // z). Their intersection holds it too; which is tighter depends on the chart (a strongly
  // stretched or mirrored one turns the box far more than it stretches the sphere).
  const dvec3 e = h + d.e * (glm::abs(c) + h) + pad;
  const dvec3 radius = dvec3(sigma * r, sigma * r, r) + pad;
  // The copy without the lift: its atoms, turned by the normal's tilt.
  const dvec3 atoms_lo = glm::max(pos + c - e, pos - radius) - dvec3(turn_xy, turn_xy, std::max(turn_z, 0.0) + slack);
  const dvec3 atoms_hi = glm::min(pos + c + e, pos + radius) + dvec3(turn_xy, turn_xy, std::max(-turn_z, 0.0) + slack);
  CopyBoxes out;
  out.reach_lo = atoms_lo - dvec3(lift_xy, lift_xy, -d.lift_lo);
  out.reach_hi = atoms_hi + dvec3(lift_xy, lift_xy, d.lift_hi);
  // Moved onto the tile's lift plane, p' = p − plane(p.x, p.y): the centre keeps the curvature term
  // lift(uv_m) − plane(pos) (unsheared triangles: the whole lift), and a point at (x, y) off the
  // centre also meets the plane's slopes times that offset.
  dvec3 lift_lo(INFINITY), lift_hi(-INFINITY);
  if (d.has_sheared()) {
    const dvec2 delta_c = dvec2(pos) - half;
    dvec3 q_lo, q_hi;
    for (int k = 0; k < 3; ++k) std::tie(q_lo[k], q_hi[k]) = curvature_range(d.curvature_lo[k], d.curvature_hi[k], delta_c);
    const dvec2 across = glm::max(glm::abs(dvec2(atoms_lo) - dvec2(pos)), glm::abs(dvec2(atoms_hi) - dvec2(pos))) +
                         glm::max(glm::abs(dvec2(q_lo)), glm::abs(dvec2(q_hi)));
    const dvec3 tilt = d.slope_x * across.x + d.slope_y * across.y + d.plane_error;
    lift_lo = q_lo - tilt, lift_hi = q_hi + tilt;
  }
  if (d.has_unsheared()) {
    lift_lo = glm::min(lift_lo, dvec3(-lift_xy, -lift_xy, d.unsheared_lo));
    lift_hi = glm::max(lift_hi, dvec3(lift_xy, lift_xy, d.unsheared_hi));
  }
  out.lo = atoms_lo + lift_lo;
  out.hi = atoms_hi + lift_hi;
  return out;
}

}  // namespace nano::placement
