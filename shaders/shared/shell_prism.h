// The adaptive shell prism of one proxy triangle (paper §"Adaptive Shell Space Construction",
// ALGORITHMS.md §3). Per triangle the package stores three offsets (+h, −h, side); the prism is
// rebuilt from them and the triangle's corners and unit vertex normals wherever it is needed (BLAS
// AABBs, the shader's prism test, the CPU oracle), so this header is the single definition.
// GLSL 460 and C++20/GLM.
//
//  * bottom cap: P_i − h_minus·n_i; top cap: P_i + h_plus·n_i (n_i unit vertex normals). The heights
//    are along the vertex normals, so they are NOT heights above the face: the baker divides by the
//    cosine between vertex and face normal (bake/shell/shell_offsets.cpp).
//  * each cap triangle is then grown in its own plane so that each of its edge lines moves outward
//    by `side` (the overlap of the paper): the offset edge lines meet on the in-plane angle bisector
//    at distance side / sin(θ_i/2) from the vertex, θ_i the cap's interior angle there. For sliver
//    angles that factor explodes; it is clamped to kShellMaxMiter (θ ≲ 29°), so at such a corner the
//    edges move by less than `side` near the vertex — the baker verifies containment against the
//    clamped prism and grows `side` until it holds, so the clamp only costs a wider prism.
//  * side = 0 gives the "no overlap" prism; fixed shells use the maxima over all triangles.
#ifndef NANO_SHELL_PRISM_H
#define NANO_SHELL_PRISM_H
#include "shared/placement_common.h"
#include "shared/ray_prism.h"

NANO_BEGIN

// Largest factor side·k a cap vertex moves by (k = 1/sin(θ/2) for an exact miter; 4 ⇔ θ ≈ 29°).
NANO_CONST float kShellMaxMiter = 4.0f;

// Per-triangle shell offsets (Å). All zero for a triangle that owns no molecule (flat prism: the
// runtime may skip it).
struct ShellOffsets {
  float h_plus;   // along +n_i to the top cap
  float h_minus;  // along −n_i to the bottom cap
  float side;     // in-plane outward offset of every cap edge
};

// Displacement of cap vertex p (neighbours q, r) that moves both its edge lines outward by `side`:
// −bisector·side·min(1/sin(θ/2), kShellMaxMiter). Zero for a degenerate corner (coincident or
// collinear points), where no in-plane outward direction exists.
NANO_FN vec3 shell_miter_offset(NANO_IN(vec3) p, NANO_IN(vec3) q, NANO_IN(vec3) r, float side) {
  vec3 a = q - p;
  vec3 b = r - p;
  float la = length(a);
  float lb = length(b);
  if (!(la > 0.0f) || !(lb > 0.0f)) return vec3(0.0f);
  a = a / la;
  b = b / lb;
  vec3 bis = a + b;  // points into the triangle
  float lbis = length(bis);
  float sin_half = 0.5f * length(a - b);
  if (!(lbis > 0.0f) || !(sin_half > 0.0f)) return vec3(0.0f);
  float k = min(1.0f / sin_half, kShellMaxMiter);
  return bis * (-side * k / lbis);
}

// The prism of triangle (P0, P1, P2) with unit vertex normals (n0, n1, n2) in the vertex order of
// ray_prism.h: v[0..2] bottom cap over corners 0, 1, 2; v[3..5] top cap over the same corners.
NANO_FN Prism shell_prism_make(NANO_IN(vec3) P0, NANO_IN(vec3) P1, NANO_IN(vec3) P2, NANO_IN(vec3) n0,
                               NANO_IN(vec3) n1, NANO_IN(vec3) n2, NANO_IN(ShellOffsets) off) {
  Prism pr;
  pr.v[0] = P0 - off.h_minus * n0;
  pr.v[1] = P1 - off.h_minus * n1;
  pr.v[2] = P2 - off.h_minus * n2;
  pr.v[3] = P0 + off.h_plus * n0;
  pr.v[4] = P1 + off.h_plus * n1;
  pr.v[5] = P2 + off.h_plus * n2;
  for (int cap = 0; cap < 2; ++cap) {
    int i = cap * 3;
    vec3 a = pr.v[i];
    vec3 b = pr.v[i + 1];
    vec3 c = pr.v[i + 2];
    // All three offsets from the ungrown cap, so the corners do not depend on each other's order.
    pr.v[i] = a + shell_miter_offset(a, b, c, off.side);
    pr.v[i + 1] = b + shell_miter_offset(b, c, a, off.side);
    pr.v[i + 2] = c + shell_miter_offset(c, a, b, off.side);
  }
  return pr;
}

// Componentwise maximum: the fixed-height shell is the maximum of the per-triangle offsets.
NANO_FN ShellOffsets shell_offsets_max(NANO_IN(ShellOffsets) a, NANO_IN(ShellOffsets) b) {
  ShellOffsets r;
  r.h_plus = max(a.h_plus, b.h_plus);
  r.h_minus = max(a.h_minus, b.h_minus);
  r.side = max(a.side, b.side);
  return r;
}

NANO_END
#endif
