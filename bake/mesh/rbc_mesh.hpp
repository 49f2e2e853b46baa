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
// UV layout: the top and bottom halves are two disks of radius 0.24 centred at (0.25, 0.5) and
// (0.75, 0.5); a vertex's UV radius is its arc length from the pole (azimuthal equidistant), so
// the meridional stretch is exactly uniform and the circumferential stretch is r / s. The bottom
// disk is mirrored so both disks wind like the outward surface. The only seam is the rim.
// The edge length is corrected until the triangle count is within 5% of the target or 8 rounds
// have passed (3,000 gives 2,828); the ±25% contract is tested. Throws nano::InputError if target < 200.
ProxyMesh make_rbc_mesh(int target_triangles, const EvansFungShape& shape = {});

}  // namespace nano::mesh
