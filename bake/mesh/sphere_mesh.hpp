#pragma once
#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

// Virion proxy: an equal-angle cube-sphere. Each cube face is an n×n grid whose parameters
// (a, b) ∈ [−1, 1]² map to the cube point tan(a·π/4), tan(b·π/4) before projection onto the
// sphere; that warp makes the grid lines equally spaced in angle, so cells vary in area by
// ~1.4× instead of the ~5× of a plain gnomonic cube map.
// UV layout: each face's chart is the azimuthal equidistant projection about the face centre
// (UV radius ∝ angle from the centre, along the same azimuth), scaled so that the edge midpoints
// (45°) reach its cell of a 3×2 atlas (cells of 1/3 × 1/3, so v ∈ [0, 2/3]) inset by a gutter of
// 0.02; charts are rounded squares whose corners (54.7°) stay inside. Radial stretch is constant
// and the tangential one falls as sin θ / θ, so σ_max / σ_min ≤ 0.955 / sin 0.955 ≈ 1.17 (plus the
// chords' discretisation) — against ≈ 1.58 for UVs linear in (a, b), whose cells become 120°
// rhombi at the cube corners. A low ratio matters: membrane tiles are packed to survive the whole
// range (tiles::MembraneTileRequest::lateral_stretch), which costs density. Not mirrored (UV
// winding = outward winding). Seams: all 12 cube edges. Positions are shared along them; UVs are not.
// 12·n² triangles with n = round(sqrt(target / 12)); normals are angle-weighted vertex normals.
// Throws nano::InputError when target < 48 or radius is not positive and finite.
ProxyMesh make_sphere_mesh(int target_triangles, double radius);

}  // namespace nano::mesh
