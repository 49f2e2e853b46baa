#pragma once
// The Evans–Fung biconcave red blood cell (shared/data/BIOLOGY.md §1.2):
//   z(ρ) = ±(R0/2)·sqrt(1 − ρ²)·(C0 + C1ρ² + C2ρ⁴),  ρ = r / R0.
// The mesh is in ångström (the project's length unit): 1 µm = 10⁴ Å.
#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

struct EvansFungShape {
  double r0 = 3.91e4;  // Å (3.91 µm)
  double c0 = 0.2072, c1 = 2.0026, c2 = -1.1228;

  // Half thickness z ≥ 0 at distance r from the axis (0 ≤ r ≤ r0).
  double half_thickness(double r) const;
};

inline constexpr double angstrom_per_micrometre = 1.0e4;

// Closed surface of revolution, sampled along the meridian r = R0·sin θ,
// z = (R0/2)·cos θ·(C0 + C1 sin²θ + C2 sin⁴θ), θ ∈ [0, π] (this parameter removes the sqrt
// singularity at the rim). Rings are spaced evenly in a curvature-weighted arc length
// ∫ (1 + ℓc·|κ|) ds with ℓc = 0.5 µm, so the rim (radius of curvature ≈ 1.15 µm) gets up to
// ~1.4× more rings per unit length; each ring gets as many vertices as make near-equilateral
// triangles. The rim θ = π/2 is always a ring, and the bottom half mirrors the top.
// UV layout: bands of whole rings, each unrolled with meridional stretch exactly 1 and nearly
// the same circumferential stretch, so that every chart is close to isotropic. S is the length
// along the ring polyline from the top pole. A polar cap is azimuthal equidistant about its pole
// (UV radius S, circumferential stretch r / S). A band symmetric about the rim is a cylinder cut
// open (u = r̄·φ, v = −S), so the rim is no seam unless the mesh is too coarse for that band.
// Every other band is the cone through its two boundary rings (r ≈ α·S + β), unrolled about its
// apex (UV radius (α·S + β) / |α|, angle α·φ) and cut along the zigzag of each ring's vertex 0;
// a cone with |α| > 0.95 is cut into two sectors. Bands are as wide as keeps each chart's
// max σ1 / min σ2 ≤ 1.03, and mirrored on the lower half; each chart is then scaled so that its
// smallest stretch is the same, which bounds the mesh's chart_anisotropy by that 1.03 wherever a
// single ring gap fits it (from ~600 triangles; 200 give 1.05). 3,000 triangles: 7 charts (2 caps,
// 2 cones per half, the rim cylinder), anisotropy 1.029, seams 4.5× the rim circumference. The
// charts are shelf-packed into [0,1]² with gutters, all counter-clockwise like the outward surface.
// The edge length is corrected until the triangle count is within 5% of the target or 8 rounds
// have passed (3,000 gives 2,828); the ±25% contract is tested. Throws nano::InputError if target < 200.
ProxyMesh make_rbc_mesh(int target_triangles, const EvansFungShape& shape = {});

}  // namespace nano::mesh
