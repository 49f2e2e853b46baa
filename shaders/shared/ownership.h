// Watertight ownership of UV points by UV triangles (ALGORITHMS.md §1): each molecule of the
// replicated Wang tiling belongs to exactly one triangle of a UV chart.
//
// How it stays exact without doubles (shaders have none):
//  * UV coordinates are snapped to a fixed grid of 2^-24 (own_quantize: floor(uv·2^24), exact in
//    float because 2^24 is a power of two). |uv| must stay below 16 (quantised |q| ≤ 2^28; larger
//    values are clamped, which keeps the partition property but makes far points meaningless).
//    Float UVs in [0.5, 16) already lie on that grid; the baker should snap smaller UVs to
//    multiples of 2^-24 so the quantised chart is exactly the stored chart (see report).
//  * orient2d on those integers is evaluated EXACTLY: coordinate differences fit in 30 bits, the
//    two products are formed as 64-bit values with imulExtended and compared as (hi, lo) pairs.
//  * Each edge is evaluated with a CANONICAL direction (endpoints ordered lexicographically), so two
//    triangles sharing the edge compute the same value for it.
//  * Ties (point exactly on an edge line) follow a symbolic perturbation p → p + (−ε², ε): a point on
//    a canonical edge lo→hi is treated as lying on its LEFT. Because this is one global perturbation
//    of the point, every point of the plane is owned by exactly one triangle of any tessellation
//    (no duplicates, no drops), including points on shared edges and shared vertices, and the
//    rule is independent of triangle winding (mirrored charts work). Zero-area triangles own nothing.
//  Points on the outer boundary of a chart are owned iff p + (−ε², ε) lies inside it.
#ifndef NANO_OWNERSHIP_H
#define NANO_OWNERSHIP_H
#include "shared/placement_common.h"

NANO_BEGIN

NANO_CONST float kOwnQuantScale = 16777216.0f;  // 2^24 grid steps per UV unit
NANO_CONST float kOwnQuantLimit = 268435456.0f;  // 2^28: |uv| < 16

// UV (float) → integer grid point floor(uv·2^24), clamped to ±2^28. Deterministic and exact.
NANO_FN ivec2 own_quantize(NANO_IN(vec2) uv) {
  vec2 q = clamp(floor(uv * kOwnQuantScale), vec2(-kOwnQuantLimit), vec2(kOwnQuantLimit));
  return ivec2(q);
}

// Exact sign of a·b − c·d for 32-bit ints (any values): −1, 0 or +1.
NANO_FN int own_sign_diff_products(int a, int b, int c, int d) {
  int h1; int l1; int h2; int l2;
  imulExtended(a, b, h1, l1);
  imulExtended(c, d, h2, l2);
  if (h1 != h2) return h1 > h2 ? 1 : -1;
  uint u1 = uint(l1);
  uint u2 = uint(l2);
  if (u1 != u2) return u1 > u2 ? 1 : -1;
  return 0;
}

// Exact sign of orient2d(a, b, p) = (b − a) × (p − a) for quantised points (|coords| ≤ 2^28):
// +1 if p is left of a→b, −1 right, 0 collinear.
NANO_FN int own_orient_q(NANO_IN(ivec2) a, NANO_IN(ivec2) b, NANO_IN(ivec2) p) {
  return own_sign_diff_products(b.x - a.x, p.y - a.y, b.y - a.y, p.x - a.x);
}

// True iff a precedes b lexicographically (x first, then y).
NANO_FN bool own_lex_less(NANO_IN(ivec2) a, NANO_IN(ivec2) b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

// Side of p with respect to the CANONICAL line of edge {a, b} (directed from the lexicographically
// smaller endpoint to the larger): +1 left or on the line (tie rule), −1 right. The value does not
// depend on the order in which a and b are given.
NANO_FN int own_edge_side_q(NANO_IN(ivec2) a, NANO_IN(ivec2) b, NANO_IN(ivec2) p) {
  int s = own_lex_less(a, b) ? own_orient_q(a, b, p) : own_orient_q(b, a, p);
  return s >= 0 ? 1 : -1;
}

// Side (+1 / −1) of the triangle's interior with respect to the canonical line of edge {a, b}, c the
// opposite vertex; 0 if the triangle is degenerate (then it owns nothing).
NANO_FN int own_edge_inner_q(NANO_IN(ivec2) a, NANO_IN(ivec2) b, NANO_IN(ivec2) c) {
  return own_lex_less(a, b) ? own_orient_q(a, b, c) : own_orient_q(b, a, c);
}

// Ownership on quantised coordinates: true iff the UV triangle (t0, t1, t2) (either winding) owns p.
// Guarantee: over any set of triangles tessellating a region (edge-to-edge or not, interiors disjoint),
// each point of the region's interior is owned by exactly one triangle.
NANO_FN bool own_triangle_owns_q(NANO_IN(ivec2) t0, NANO_IN(ivec2) t1, NANO_IN(ivec2) t2, NANO_IN(ivec2) p) {
  int i0 = own_edge_inner_q(t0, t1, t2);
  if (i0 == 0) return false;  // degenerate: all three orientations are 0
  if (own_edge_side_q(t0, t1, p) != i0) return false;
  if (own_edge_side_q(t1, t2, p) != own_edge_inner_q(t1, t2, t0)) return false;
  return own_edge_side_q(t2, t0, p) == own_edge_inner_q(t2, t0, t1);
}

// Same on float UVs (quantised with own_quantize first). UV units, |uv| < 16.
NANO_FN bool own_triangle_owns(NANO_IN(vec2) t0, NANO_IN(vec2) t1, NANO_IN(vec2) t2, NANO_IN(vec2) p) {
  return own_triangle_owns_q(own_quantize(t0), own_quantize(t1), own_quantize(t2), own_quantize(p));
}

NANO_END
#endif
