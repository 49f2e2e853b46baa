// Ray–prism intersection for the shell (ALGORITHMS.md §3). A prism is given by six points: the bottom
// cap (base triangle offset by −h along the vertex normals) and the top cap (+h); adaptive heights,
// side extrusion for overlap etc. are the caller's business. The three walls are bilinear patches
// (generally not planar), intersected with Reshetov's method (Ray Tracing Gems ch. 8); the caps with
// Möller–Trumbore. GLSL 460 and C++20/GLM. Rays: o + t·d, d NOT normalised.
//
// Robustness policy: parameter ranges of caps ([barycentrics ≥ −ε]) and walls ([−ε, 1+ε]²) are
// widened by kPrismParamEps so a ray through a shared edge or vertex is reported by at least one
// face (duplicates are harmless: the result is the hull [min t, max t]); inside/outside of the origin
// is decided from the orientation of the NEAREST hit (exit ⇒ inside), which duplicates do not break.
#ifndef NANO_RAY_PRISM_H
#define NANO_RAY_PRISM_H
#include "shared/placement_common.h"

NANO_BEGIN

// Relative widening of face parameter ranges (fraction of an edge length).
NANO_CONST float kPrismParamEps = 1e-5f;

// v[0..2] = bottom cap (−h) over base vertices 0,1,2; v[3..5] = top cap (+h) over the same vertices.
// Wall i joins base edge (i, i+1 mod 3): bilinear patch p00 = v[i], p10 = v[i+1], p01 = v[i+3],
// p11 = v[i+1+3]. Contract: the prism is not inverted (each top vertex lies on the top side, caps do
// not cross); winding of the base may be either.
struct Prism {
  vec3 v[6];
};

// Ray vs triangle (a, b, c) over the whole line (any t). True if the line crosses the plane inside
// the triangle widened by `eps` in barycentric units; t (units of d), barycentrics (u, v) of b and c.
// False for a ray parallel to the plane (det = 0).
NANO_FN bool prism_ray_triangle(NANO_IN(vec3) o, NANO_IN(vec3) d, NANO_IN(vec3) a, NANO_IN(vec3) b,
                        NANO_IN(vec3) c, float eps, NANO_OUT(float) t, NANO_OUT(float) u,
                        NANO_OUT(float) v) {
  t = 0.0f;
  u = 0.0f;
  v = 0.0f;
  vec3 e1 = b - a;
  vec3 e2 = c - a;
  vec3 pv = cross(d, e2);
  float det = dot(e1, pv);
  if (det == 0.0f) return false;
  float inv = 1.0f / det;
  vec3 tv = o - a;
  u = dot(tv, pv) * inv;
  vec3 qv = cross(tv, e1);
  v = dot(d, qv) * inv;
  t = dot(e2, qv) * inv;
  return u >= -eps && v >= -eps && u + v <= 1.0f + eps && abs(t) <= placement_flt_max();
}

// Ray vs bilinear patch p00, p10, p01, p11 (X(u,v) = lerp(lerp(p00,p10,u), lerp(p01,p11,u), v)),
// over the whole line (any t). Reshetov's quadratic in u: A u² + B u + C = 0 with
// A = ((p10−p00)×(p01−p11))·d, C = ((p00−o)×d)·(p01−p00), B = ((p10−o)×d)·(p11−p10) − A − C,
// stable roots; for each root u ∈ [−eps, 1+eps], v and t from the closest point of the ray and the
// segment at u, accepted if v ∈ [−eps, 1+eps]. Returns the number of hits (0, 1, 2); hits are
// (t0, u0, v0) then (t1, u1, v1). Planar parallelogram walls (A = 0) are handled (linear case).
NANO_FN int prism_ray_patch(NANO_IN(vec3) o, NANO_IN(vec3) d, NANO_IN(vec3) p00, NANO_IN(vec3) p10,
                    NANO_IN(vec3) p01, NANO_IN(vec3) p11, float eps, NANO_OUT(vec3) hit0,
                    NANO_OUT(vec3) hit1) {
  hit0 = vec3(0.0f);
  hit1 = vec3(0.0f);
  vec3 q00 = p00 - o;
  vec3 q10 = p10 - o;
  vec3 e10 = p10 - p00;
  vec3 e11 = p11 - p10;
  vec3 e00 = p01 - p00;
  NANO_PRECISE float qa = dot(cross(e10, p01 - p11), d);
  NANO_PRECISE float qc = dot(cross(q00, d), e00);
  NANO_PRECISE float qb = dot(cross(q10, d), e11) - qa - qc;
  NANO_PRECISE float disc = qb * qb - 4.0f * qa * qc;
  if (disc < 0.0f) return 0;
  float sq = sqrt(disc);
  float q = -0.5f * (qb + (qb >= 0.0f ? sq : -sq));
  // The two roots in a fixed order (q/A, then C/q), each with its own validity: no array indexed by
  // a count, which a SIMD driver turns into scratch memory or if-ladders.
  bool has_root0 = qa != 0.0f;
  bool has_root1 = q != 0.0f;
  if (!has_root1 && qa == 0.0f && qb == 0.0f) return 0;  // degenerate: no isolated solution
  float root0 = q / (has_root0 ? qa : 1.0f);
  float root1 = qc / (has_root1 ? q : 1.0f);
  int count = 0;
  for (int k = 0; k < 2; ++k) {
    if (!(k == 0 ? has_root0 : has_root1)) continue;
    float u = k == 0 ? root0 : root1;
    if (!(u >= -eps && u <= 1.0f + eps)) continue;
    vec3 pa = mix(q00, q10, u);   // bottom point (relative to o)
    vec3 pb = mix(e00, e11, u);  // segment direction at u: lerp(p01−p00, p11−p10, u)
    vec3 n = cross(d, pb);
    float nn = dot(n, n);
    if (!(nn > 0.0f)) continue;
    vec3 m = cross(n, pa);
    float t = dot(m, pb) / nn;
    float v = dot(m, d) / nn;
    if (!(v >= -eps && v <= 1.0f + eps)) continue;
    if (count == 0) hit0 = vec3(t, u, v); else hit1 = vec3(t, u, v);
    count += 1;
  }
  return count;
}

// Result of prism_intersect.
struct PrismInterval {
  float t_enter;       // max(t_min, first face hit): t_min when the origin is inside
  float t_exit;        // last face hit, clipped to t_max
  int hit_count;       // face hits with t > t_min (any t_max), duplicates at edges included
  bool origin_inside;  // see prism_intersect
};

// Ray o + t·d vs prism over [t_min, t_max]. True iff some face is met beyond t_min and the hull
// [t_enter, t_exit] of the face hits (with t_enter = t_min if the origin is inside) meets
// [t_min, t_max]. The ray's part inside the prism is contained in [t_enter, t_exit] (for twisted walls
// it may be several pieces). Inside/outside of the origin: face hits are sorted by t and grouped into
// clusters closer than kPrismClusterEps·(prism size)/|d|; the first cluster whose orientations do not
// cancel (entries −1, exits +1) decides: an exit ⇒ inside. This is robust to duplicate hits where
// a ray crosses an edge or vertex (reported by two widened faces) and to grazing touches of an edge
// (an entry and an exit at the same t). Remaining failure mode: a ray passing within ~1e-5·size
// OUTSIDE an edge may hit a single widened face; if that hit is an exit the origin is wrongly taken
// as inside, giving a too-long (conservative) interval — never a too-short one.
NANO_CONST float kPrismClusterEps = 1e-4f;
// At most two caps and two hits on each of three walls.
NANO_CONST int kPrismMaxHits = 8;

NANO_FN bool prism_intersect(NANO_IN(Prism) pr, NANO_IN(vec3) o, NANO_IN(vec3) d, float t_min, float t_max,
                     NANO_OUT(PrismInterval) r) {
  // One slot per possible face hit — caps 0 and 1, wall w's hits 2 + 2w and 3 + 2w — so every index
  // is a constant once the loops are unrolled (no sort of a runtime-length list: on a SIMD driver that
  // is scratch memory and much of the shader's compile time). Sign 0 marks an empty slot.
  float ht[kPrismMaxHits];  // hit t
  float hs[kPrismMaxHits];  // +1 exit, −1 entry, 0 none
  for (int k = 0; k < kPrismMaxHits; ++k) {
    ht[k] = 0.0f;
    hs[k] = 0.0f;
  }
  vec3 nb = cross(pr.v[1] - pr.v[0], pr.v[2] - pr.v[0]);
  vec3 nt = cross(pr.v[4] - pr.v[3], pr.v[5] - pr.v[3]);
  vec3 up = (pr.v[3] + pr.v[4] + pr.v[5]) - (pr.v[0] + pr.v[1] + pr.v[2]);
  // orient = +1 if the base runs counter-clockwise seen from the top.
  float orient = dot(nb + nt, up) >= 0.0f ? 1.0f : -1.0f;
  vec3 bmin = pr.v[0];
  vec3 bmax = pr.v[0];
  for (int k = 1; k < 6; ++k) { bmin = min(bmin, pr.v[k]); bmax = max(bmax, pr.v[k]); }
  float eps_t = kPrismClusterEps * length(bmax - bmin) / length(d);
  float t; float bu; float bv;
  // Caps: outward normal −orient·nb (bottom), +orient·nt (top).
  for (int cap = 0; cap < 2; ++cap) {
    int i = cap * 3;
    if (prism_ray_triangle(o, d, pr.v[i], pr.v[i + 1], pr.v[i + 2], kPrismParamEps, t, bu, bv) && t > t_min) {
      vec3 outward = cap == 0 ? -orient * nb : orient * nt;
      ht[cap] = t;
      hs[cap] = dot(outward, d) > 0.0f ? 1.0f : -1.0f;
    }
  }
  for (int w = 0; w < 3; ++w) {
    int j = w == 2 ? 0 : w + 1;
    vec3 p00 = pr.v[w]; vec3 p10 = pr.v[j]; vec3 p01 = pr.v[w + 3]; vec3 p11 = pr.v[j + 3];
    vec3 h0; vec3 h1;
    int n = prism_ray_patch(o, d, p00, p10, p01, p11, kPrismParamEps, h0, h1);
    for (int k = 0; k < 2; ++k) {
      vec3 h = k == 0 ? h0 : h1;
      if (k >= n || !(h.x > t_min) || !(abs(h.x) <= placement_flt_max())) continue;
      // ∂X/∂u × ∂X/∂v points outward for a counter-clockwise base seen from the top.
      vec3 du = mix(p10 - p00, p11 - p01, h.z);
      vec3 dv = mix(p01 - p00, p11 - p10, h.y);
      ht[2 + 2 * w + k] = h.x;
      hs[2 + 2 * w + k] = orient * dot(cross(du, dv), d) > 0.0f ? 1.0f : -1.0f;
    }
  }
  int count = 0;
  float t_first = placement_inf();
  float t_last = -placement_inf();
  for (int k = 0; k < kPrismMaxHits; ++k) {
    if (hs[k] == 0.0f) continue;
    count += 1;
    t_first = min(t_first, ht[k]);
    t_last = max(t_last, ht[k]);
  }
  // Clusters in order of t: all hits within eps_t of the nearest one not yet seen; the first whose
  // signs do not cancel decides. Each round moves past at least one hit, so kPrismMaxHits bound it.
  bool inside = false;
  float start = t_first;
  for (int round = 0; round < kPrismMaxHits && start <= t_last; ++round) {
    float sum = 0.0f;
    float next = placement_inf();
    for (int k = 0; k < kPrismMaxHits; ++k) {
      if (hs[k] == 0.0f || ht[k] < start) continue;
      if (ht[k] - start <= eps_t) sum += hs[k];
      else next = min(next, ht[k]);
    }
    if (sum != 0.0f) {
      inside = sum > 0.0f;
      break;
    }
    start = next;
  }
  r.hit_count = count;
  r.origin_inside = inside;
  r.t_enter = count == 0 ? t_max : (inside ? t_min : max(t_first, t_min));
  r.t_exit = count == 0 ? t_min : min(t_last, t_max);
  return count > 0 && r.t_enter <= r.t_exit;
}

NANO_END
#endif
