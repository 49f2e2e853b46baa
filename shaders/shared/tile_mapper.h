// Wang tile mapper (ALGORITHMS.md §1): UV chart of one proxy triangle → world, the tile frame M1,
// the molecule placements M2 (membrane and soluble) and the replication area. GLSL 460 and C++20/GLM.
//
// Units: world lengths in Å; UV in chart units; tile space in Å with (x, y) ∈ [0, S)² the tile
// square and z the height above the surface (along the normal). s = S / k is the tile's UV size
// (k = global scale, Å per UV unit); functions take the ratio s_over_S = s / S (UV units per Å).
// Precision: pass triangle corners relative to the camera (or the compartment instance origin), not
// in absolute scene coordinates, when the scene is far from the origin (ALGORITHMS.md §5).
#ifndef NANO_TILE_MAPPER_H
#define NANO_TILE_MAPPER_H
#include "shared/placement_common.h"
#include "shared/quaternion.h"

NANO_BEGIN

// Everything the mapper needs about one triangle, derived once by chart_make.
struct TriangleChart {
  vec3 p0;           // world corners (Å)
  vec3 p1;
  vec3 p2;
  vec3 ju;           // J column ∂X/∂u (Å per UV unit)
  vec3 jv;           // J column ∂X/∂v
  vec2 t0;           // UV of P0
  vec2 einv_row0;    // rows of E⁻¹: barycentrics (λ1, λ2) = E⁻¹ (uv − t0)
  vec2 einv_row1;
  vec3 n0;           // vertex normals (any length, interpolated then normalised)
  vec3 n1;
  vec3 n2;
  vec3 face_normal;  // unit normal of (P1−P0)×(P2−P0): the mesh winding decides "outward"
  float det_e;       // det E = det[t1−t0 | t2−t0]; < 0: mirrored chart; 0: unusable triangle
};

// Builds the chart of triangle (P0, P1, P2) with UVs (t0, t1, t2) and vertex normals (n0, n1, n2).
// E = [t1−t0 | t2−t0], F = [P1−P0 | P2−P0], J = F·E⁻¹. Contract: the UV triangle and the world
// triangle are non-degenerate (chart_valid tells); otherwise the fields hold inf/NaN.
NANO_FN TriangleChart chart_make(NANO_IN(vec3) P0, NANO_IN(vec3) P1, NANO_IN(vec3) P2, NANO_IN(vec2) t0,
                         NANO_IN(vec2) t1, NANO_IN(vec2) t2, NANO_IN(vec3) n0, NANO_IN(vec3) n1,
                         NANO_IN(vec3) n2) {
  TriangleChart c;
  vec2 a = t1 - t0;
  vec2 b = t2 - t0;
  vec3 f1 = P1 - P0;
  vec3 f2 = P2 - P0;
  float det = a.x * b.y - a.y * b.x;
  float inv = 1.0f / det;
  c.p0 = P0;
  c.p1 = P1;
  c.p2 = P2;
  c.t0 = t0;
  c.det_e = det;
  c.einv_row0 = vec2(b.y, -b.x) * inv;
  c.einv_row1 = vec2(-a.y, a.x) * inv;
  // J = F·E⁻¹: column 0 of E⁻¹ is (b.y, −a.y)/det, column 1 is (−b.x, a.x)/det.
  c.ju = (f1 * b.y - f2 * a.y) * inv;
  c.jv = (f2 * a.x - f1 * b.x) * inv;
  c.n0 = n0;
  c.n1 = n1;
  c.n2 = n2;
  c.face_normal = normalize(cross(f1, f2));
  return c;
}

// True iff the chart is usable (non-degenerate UV and world triangle, finite J).
NANO_FN bool chart_valid(NANO_IN(TriangleChart) c) {
  float m = abs(c.ju.x) + abs(c.ju.y) + abs(c.ju.z) + abs(c.jv.x) + abs(c.jv.y) + abs(c.jv.z) +
            abs(c.face_normal.x) + abs(c.face_normal.y) + abs(c.face_normal.z);
  return c.det_e != 0.0f && m <= placement_flt_max();  // false for inf and NaN
}

// Barycentric coordinates (λ0, λ1, λ2) of uv, Σ = 1; negative outside the UV triangle.
NANO_FN vec3 chart_barycentric(NANO_IN(TriangleChart) c, NANO_IN(vec2) uv) {
  vec2 w = uv - c.t0;
  float l1 = dot(c.einv_row0, w);
  float l2 = dot(c.einv_row1, w);
  return vec3(1.0f - l1 - l2, l1, l2);
}

// X(uv) = P0 + J·(uv − t0): the affine extension of the triangle (valid with negative barycentrics,
// i.e. for tiles hanging over the triangle's edges). Å.
NANO_FN vec3 chart_position(NANO_IN(TriangleChart) c, NANO_IN(vec2) uv) {
  vec2 w = uv - c.t0;
  return c.p0 + c.ju * w.x + c.jv * w.y;
}

// The smooth surface membrane copies stand on: Phong tessellation (Boubekeur & Alexa 2008) of the
// corner normals, X = p − α·Σ λ_i ((p − P_i)·n̂_i) n̂_i with p = X(uv) the flat point, λ its
// barycentrics and α the shape factor (0: the flat facet, format ≤ 2.2; the baker uses 1/2, which
// lifts a sphere's facets onto the sphere to second order). On an edge only that edge's two corners
// weigh, so neighbouring triangles agree along it; at a corner the surface passes through it. Copies placed on it stand along interpolated normals
// that nearly follow its own, which flat facets (tilted by up to half the dihedral angle) do not.
NANO_FN vec3 chart_smooth_position(NANO_IN(TriangleChart) c, NANO_IN(vec2) uv, float alpha) {
  vec3 p = chart_position(c, uv);
  if (alpha == 0.0f) return p;
  vec3 l = chart_barycentric(c, uv);
  vec3 m0 = normalize(c.n0);
  vec3 m1 = normalize(c.n1);
  vec3 m2 = normalize(c.n2);
  vec3 lift = (l.x * dot(p - c.p0, m0)) * m0 + (l.y * dot(p - c.p1, m1)) * m1 + (l.z * dot(p - c.p2, m2)) * m2;
  return p - alpha * lift;
}

// Bound on |chart_smooth_position − chart_position| over the triangle (barycentrics in [0, 1]):
// α·max over corners i, j of |(P_j − P_i)·n̂_i| (each lift term is linear in p, largest at a corner).
NANO_FN float chart_smooth_bulge(NANO_IN(TriangleChart) c, float alpha) {
  vec3 m0 = normalize(c.n0);
  vec3 m1 = normalize(c.n1);
  vec3 m2 = normalize(c.n2);
  float b = max(max(abs(dot(c.p1 - c.p0, m0)), abs(dot(c.p2 - c.p0, m0))),
                max(max(abs(dot(c.p0 - c.p1, m1)), abs(dot(c.p2 - c.p1, m1))),
                    max(abs(dot(c.p0 - c.p2, m2)), abs(dot(c.p1 - c.p2, m2)))));
  return alpha * b;
}

// The lift X_smooth − X_flat = −α Σ_i l_i ((p − P_i)·m_i) m_i is a quadratic in the barycentrics:
// Σ_i m_i·l_i·Σ_j k_ij l_j with k_ij = −α (P_j − P_i)·m_i (as p − P_i = Σ_j l_j (P_j − P_i)), m_i the
// unit corner normals. Returns the k_ij as columns: result[j][i] = k_ij (k_ii = 0). Exact anywhere
// in the plane, inside the triangle or not.
NANO_FN mat3 chart_smooth_lift_coefficients(NANO_IN(TriangleChart) c, float alpha) {
  vec3 p[3];
  vec3 m[3];
  p[0] = c.p0; p[1] = c.p1; p[2] = c.p2;
  m[0] = normalize(c.n0); m[1] = normalize(c.n1); m[2] = normalize(c.n2);
  mat3 k = mat3(0.0f);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) k[j][i] = -alpha * dot(p[j] - p[i], m[i]);
  return k;
}

// Range [lo, hi] (lo ≤ 0 ≤ hi) of the lift's part along the face normal over the triangle:
// Σ_ij l_i l_j c_ij with c_ij = k_ij (m_i·N); the weights l_i l_j ≥ 0 sum to 1, so it lies between
// the least and largest c_ij (c_ii = 0). On a convex stretch of surface every c_ij ≥ 0: the lift only rises.
NANO_FN void chart_smooth_lift_range(NANO_IN(TriangleChart) c, float alpha, NANO_OUT(float) lo, NANO_OUT(float) hi) {
  mat3 k = chart_smooth_lift_coefficients(c, alpha);
  vec3 along = vec3(dot(normalize(c.n0), c.face_normal), dot(normalize(c.n1), c.face_normal),
                    dot(normalize(c.n2), c.face_normal));
  lo = 0.0f;
  hi = 0.0f;
  for (int j = 0; j < 3; ++j) {
    vec3 cj = k[j] * along;  // c_ij for i = 0, 1, 2
    lo = min(lo, min(cj.x, min(cj.y, cj.z)));
    hi = max(hi, max(cj.x, max(cj.y, cj.z)));
  }
}

// Interpolated vertex normal at uv, normalised (barycentric weights may be negative outside).
NANO_FN vec3 chart_normal(NANO_IN(TriangleChart) c, NANO_IN(vec2) uv) {
  vec3 l = chart_barycentric(c, uv);
  return normalize(c.n0 * l.x + c.n1 * l.y + c.n2 * l.z);
}

// Global scale k = sqrt(Σ world area / Σ UV area) (Å per UV unit); tile UV size s = S / k.
NANO_FN float chart_global_scale(float world_area_sum, float uv_area_sum) { return sqrt(world_area_sum / uv_area_sum); }

// Tile frame M1 of the tile whose tile-space origin sits at UV g: (x, y, z) ↦ X(g) + A·(x, y) + z·N
// with A = J·(s/S) (so tile square [0,S)² covers UV square g + [0,s)²) and N = unit face normal
// (outward by mesh winding). This equals Translate(X(g))·[T B N]·Scale·Shear of ALGORITHMS.md with
// the bitangent flipped for a mirrored chart (det E < 0): then det M1 < 0 (a reflection; rays stay
// rays, t is preserved). Molecules are never mirrored: their rotations come from chart_membrane_molecule.
NANO_FN Affine3 chart_tile_frame(NANO_IN(TriangleChart) c, NANO_IN(vec2) g, float s_over_S) {
  Affine3 m;
  m.linear = mat3(c.ju * s_over_S, c.jv * s_over_S, c.face_normal);
  m.translation = chart_position(c, g);
  return m;
}

// Inverse of the linear part of M1, computed analytically from the frame: rows (Av×N, N×Au)/det and N,
// det = (Au×Av)·N (the dual basis of Au, Av in the triangle plane; N ⟂ Au, Av).
NANO_FN mat3 chart_tile_frame_inverse_linear(NANO_IN(TriangleChart) c, float s_over_S) {
  vec3 au = c.ju * s_over_S;
  vec3 av = c.jv * s_over_S;
  vec3 n = c.face_normal;
  float inv = 1.0f / dot(cross(au, av), n);
  vec3 r0 = cross(av, n) * inv;
  vec3 r1 = cross(n, au) * inv;
  return transpose(mat3(r0, r1, n));  // mat3(cols) then transpose: r0, r1, n become rows
}

// M1⁻¹ as an affine transform (world → tile space).
NANO_FN Affine3 chart_tile_frame_inverse(NANO_IN(TriangleChart) c, NANO_IN(vec2) g, float s_over_S) {
  Affine3 m;
  m.linear = chart_tile_frame_inverse_linear(c, s_over_S);
  m.translation = -(m.linear * chart_position(c, g));
  return m;
}

// World ray (o, d) → tile-space ray of the tile at UV g: o' = M1⁻¹(o − X(g)) (difference first, for
// precision), d' = M1⁻¹ d (not normalised: t is shared with the world ray).
NANO_FN void chart_tile_inverse_ray(NANO_IN(TriangleChart) c, NANO_IN(vec2) g, float s_over_S, NANO_IN(vec3) o,
                            NANO_IN(vec3) d, NANO_OUT(vec3) o_tile, NANO_OUT(vec3) d_tile) {
  mat3 li = chart_tile_frame_inverse_linear(c, s_over_S);
  o_tile = li * (o - chart_position(c, g));
  d_tile = li * d;
}

// ∂l/∂x and ∂l/∂y of the barycentrics per tile Å (uv = g + (s/S)(x, y)).
NANO_FN vec3 chart_barycentric_dx(NANO_IN(TriangleChart) c, float s_over_S) {
  return vec3(-(c.einv_row0.x + c.einv_row1.x), c.einv_row0.x, c.einv_row1.x) * s_over_S;
}
NANO_FN vec3 chart_barycentric_dy(NANO_IN(TriangleChart) c, float s_over_S) {
  return vec3(-(c.einv_row0.y + c.einv_row1.y), c.einv_row0.y, c.einv_row1.y) * s_over_S;
}

// The corner normals' images in tile space, M1⁻¹·m_i (columns), that the lift is a combination of.
NANO_FN mat3 chart_lift_directions(NANO_IN(TriangleChart) c, float s_over_S) {
  return chart_tile_frame_inverse_linear(c, s_over_S) * mat3(normalize(c.n0), normalize(c.n1), normalize(c.n2));
}

// The tile plane of the lift (docs/rendering.md, molecule boxes that hug the membrane): in the tile
// at UV g, the lift in tile space and its derivatives along tile x and y at tile point `centre`. On a
// coarse facet the lift reaches tens of Å but over one tile it is nearly this plane: what is left,
// lift − plane, is exactly the quadratic chart_smooth_lift_curvature gives.
struct LiftPlane {
  vec3 value;
  vec3 dx;
  vec3 dy;
};
NANO_FN LiftPlane chart_smooth_lift_plane(NANO_IN(TriangleChart) c, NANO_IN(mat3) k, NANO_IN(mat3) directions,
                                          NANO_IN(vec2) g, float s_over_S, NANO_IN(vec2) centre) {
  vec3 l = chart_barycentric(c, g + s_over_S * centre);
  vec3 kl = k * l;  // (Σ_j k_ij l_j)_i
  vec3 lx = chart_barycentric_dx(c, s_over_S);
  vec3 ly = chart_barycentric_dy(c, s_over_S);
  LiftPlane plane;
  plane.value = directions * (l * kl);
  plane.dx = directions * (lx * kl + l * (k * lx));
  plane.dy = directions * (ly * kl + l * (k * ly));
  return plane;
}

// The lift's curvature in tile space: lift(centre + Δ) − plane(Δ) has component r equal to
// Δ.x²·h[r].x + 2·Δ.x·Δ.y·h[r].y + Δ.y²·h[r].z (Δ in tile Å), the same for every tile of the triangle.
NANO_FN mat3 chart_smooth_lift_curvature(NANO_IN(TriangleChart) c, NANO_IN(mat3) k, NANO_IN(mat3) directions,
                                         float s_over_S) {
  vec3 lx = chart_barycentric_dx(c, s_over_S);
  vec3 ly = chart_barycentric_dy(c, s_over_S);
  // Second order of Σ_i D_ri l_i (k l)_i along δl: Σ_i D_ri δl_i (k δl)_i, a form in δl.
  vec3 kx = k * lx;
  vec3 ky = k * ly;
  mat3 h;
  for (int r = 0; r < 3; ++r) {
    vec3 d = vec3(directions[0][r], directions[1][r], directions[2][r]);  // row r
    h[r] = vec3(dot(d, lx * kx), 0.5f * (dot(d, lx * ky) + dot(d, ly * kx)), dot(d, ly * ky));
  }
  return h;
}

// Moves a tile-space ray so that its points count from the tile's lift plane:
// p' = p − (value + dx·(p.x − centre.x) + dy·(p.y − centre.y)). Affine in p, so the ray stays a ray
// with the same t.
NANO_FN void chart_lift_shear_ray(NANO_IN(LiftPlane) plane, NANO_IN(vec2) centre, NANO_INOUT(vec3) o, NANO_INOUT(vec3) d) {
  vec3 o0 = o;
  vec3 d0 = d;
  o = o0 - plane.value - plane.dx * (o0.x - centre.x) - plane.dy * (o0.y - centre.y);
  d = d0 - plane.dx * d0.x - plane.dy * d0.y;
}

// UV position of a membrane molecule at tile-space (x, y, ·) in the tile at UV g: g + (s/S)(x, y).
// Computed from g and the tile-space position only, so every triangle evaluating the same tile and
// molecule gets bit-identical UVs (needed for watertight ownership, ownership.h).
NANO_FN vec2 chart_molecule_uv(NANO_IN(vec2) g, float s_over_S, NANO_IN(vec3) pos_tile) {
  return g + s_over_S * vec2(pos_tile.x, pos_tile.y);
}

// Right-handed orthonormal frame with z = n (unit) and x = tangent projected orthogonal to n, y = z×x.
// If the tangent is (nearly) parallel to n, any x ⟂ n is used.
NANO_FN mat3 chart_frame(NANO_IN(vec3) n, NANO_IN(vec3) tangent) {
  vec3 x = tangent - dot(tangent, n) * n;
  float l2 = dot(x, x);
  if (!(l2 > 1e-12f * dot(tangent, tangent))) {
    x = abs(n.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
    x = x - dot(x, n) * n;
    l2 = dot(x, x);
  }
  x = x * inversesqrt(l2);
  return mat3(x, cross(n, x), n);
}

// World transform (M1·M2 composed) of a membrane molecule at tile-space position pos_tile (Å) with
// rotation q (unit quaternion, tile space) in the tile at UV g, on the surface of shape factor
// `smoothness` (Compartment.scales.w, see chart_smooth_position):
//   uv_m = g + (s/S)(x, y); position = X_smooth(uv_m) + z·n(uv_m); rotation = frame(n(uv_m), Ju)·R(q).
// The rotation is proper (det +1) in every chart, mirrored or not. Returns uv_m for ownership.
// Its translation alone, X_smooth(uv_m) + z·n(uv_m): the baker's shell offsets need only centres.
NANO_FN vec3 chart_membrane_centre(NANO_IN(TriangleChart) c, NANO_IN(vec2) uv_m, float smoothness, float z,
                                   NANO_IN(vec3) n) {
  return chart_smooth_position(c, uv_m, smoothness) + z * n;
}

NANO_FN Affine3 chart_membrane_molecule(NANO_IN(TriangleChart) c, NANO_IN(vec2) g, float s_over_S, float smoothness,
                                NANO_IN(vec3) pos_tile, NANO_IN(vec4) q, NANO_OUT(vec2) uv_m) {
  uv_m = chart_molecule_uv(g, s_over_S, pos_tile);
  vec3 n = chart_normal(c, uv_m);
  Affine3 m;
  m.translation = chart_membrane_centre(c, uv_m, smoothness, pos_tile.z, n);
  mat3 f = chart_frame(n, c.ju);
  // Turn the frame by the rotation part of the chart's in-plane map G = [x y]ᵀ·J (polar
  // decomposition G = R·P): copies then see only the symmetric stretch P of their tile-space
  // offsets, not an extra turn of up to the chart's shear angle, so interleaved neighbours move
  // as little as the chart allows. A mirrored chart (det G < 0) keeps the tangent frame.
  float g00 = dot(f[0], c.ju), g01 = dot(f[0], c.jv), g10 = dot(f[1], c.ju), g11 = dot(f[1], c.jv);
  if (g00 * g11 - g01 * g10 > 0.0f) {
    float theta = atan(g10 - g01, g00 + g11);
    float ct = cos(theta), st = sin(theta);
    f = mat3(ct * f[0] + st * f[1], ct * f[1] - st * f[0], f[2]);
  }
  m.linear = f * quat_to_mat3(q);
  return m;
}

// Minimum corner of core-grid box ijk: grid_min + ijk·box_size (Å, compartment space).
NANO_FN vec3 core_box_min(NANO_IN(vec3) grid_min, NANO_IN(vec3) box_size, NANO_IN(ivec3) ijk) {
  return grid_min + vec3(ijk) * box_size;
}

// Transform (compartment space) of a soluble molecule at cube-space position pos (Å, from the box
// minimum) with rotation q: translation box_min + pos, rotation R(q). Compose with the compartment
// instance transform by affine_compose(instance, this) for the world transform.
NANO_FN Affine3 core_soluble_molecule(NANO_IN(vec3) box_min, NANO_IN(vec3) pos, NANO_IN(vec4) q) {
  Affine3 m;
  m.linear = quat_to_mat3(q);
  m.translation = box_min + pos;
  return m;
}

// Ray into molecule space for a molecule transform with a rotation as linear part (the results of
// chart_membrane_molecule and core_soluble_molecule): o' = Rᵀ(o − position), d' = Rᵀd (t preserved).
NANO_FN void molecule_inverse_ray(NANO_IN(Affine3) m, NANO_IN(vec3) o, NANO_IN(vec3) d, NANO_OUT(vec3) o_local,
                          NANO_OUT(vec3) d_local) {
  affine_rigid_inverse_ray(m, o, d, o_local, d_local);
}

// Ray through a general affine transform (e.g. a compartment instance with scale): o' = L⁻¹(o − T),
// d' = L⁻¹d. L must be invertible.
NANO_FN void affine_inverse_ray(NANO_IN(Affine3) m, NANO_IN(vec3) o, NANO_IN(vec3) d, NANO_OUT(vec3) o_local,
                        NANO_OUT(vec3) d_local) {
  mat3 li = inverse(m.linear);
  o_local = li * (o - m.translation);
  d_local = li * d;
}

// Replication area. Tile (i, j) covers UV [i·s, (i+1)·s) × [j·s, (j+1)·s). The UV box of a triangle is
// widened by kReplicationSlack tiles on each side before rounding, so a box edge that float rounding
// puts a hair past a tile boundary (e.g. uv_min = fl(3·s) < 3·s) never drops the neighbouring tile.
NANO_CONST float kReplicationSlack = 1e-4f;

// Origin cell of the replication area of a triangle whose UV box starts at uv_min: floor(uv_min/s − slack).
NANO_FN ivec2 replication_origin(NANO_IN(vec2) uv_min, float s) {
  return ivec2(floor(uv_min / s - vec2(kReplicationSlack)));
}

// Number of tiles (W, H) this triangle needs from its origin: floor(uv_max/s + slack) − origin + 1.
// Contains every tile the UV box [uv_min, uv_max] touches; at most replication_extent_bound.
NANO_FN ivec2 replication_extent(NANO_IN(vec2) uv_min, NANO_IN(vec2) uv_max, float s) {
  return ivec2(floor(uv_max / s + vec2(kReplicationSlack))) - replication_origin(uv_min, s) + ivec2(1);
}

// The bake-time size of ALGORITHMS.md with the slack: ceil((uv_max − uv_min)/s + 2·slack) + 1 per axis.
// The global W × H is the maximum of this over all triangles of the chart.
NANO_FN ivec2 replication_extent_bound(NANO_IN(vec2) uv_min, NANO_IN(vec2) uv_max, float s) {
  return ivec2(ceil((uv_max - uv_min) / s + vec2(2.0f * kReplicationSlack))) + ivec2(1);
}

// Tile index (recipe cell) and UV origin g of replication slot `slot` ∈ [0,W)×[0,H).
NANO_FN ivec2 replication_tile_index(NANO_IN(ivec2) origin, NANO_IN(ivec2) slot) { return origin + slot; }
NANO_FN vec2 replication_tile_uv(NANO_IN(ivec2) tile_index, float s) { return vec2(tile_index) * s; }

NANO_END
#endif
