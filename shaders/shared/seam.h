// The UV-seam rule (ALGORITHMS.md §1, "UV seams read unrelated recipe regions"): across a mesh edge
// whose two triangles do not share the edge's UVs, the two triangles map unrelated regions of the
// Wang tiling, so molecules of both sides can overlap in space. For every such seam edge exactly one
// of the two triangles YIELDS and drops its molecules near the seam; the other keeps everything.
// GLSL 460 and C++20/GLM (glsl_cpp.h); the baker's enumerator (bake/shell/membrane_mapping.hpp), the
// explicit-instancing oracle (runtime/explicit) and the shader call this same function on the same
// floats, so all three drop exactly the same copies.
//
// Which side yields (the baker decides, the package stores the outcome): the triangle whose UV chart
// (faces joined across non-seam edges) has the larger id, ids in order of each chart's lowest face;
// within one chart (a chart cut against itself) the larger triangle index. One side then yields
// along the whole seam between two charts, and where three charts meet the yields cannot form a cycle.
//
// Bits of TriangleShell.seam_edges (all others zero; the validator checks it):
//  * bit k (0-2): EDGE k of the triangle, between its corners k and (k + 1) mod 3 (edge 0: corners
//    0–1, edge 1: 1–2, edge 2: 2–0; corner order of the "triangles" section), is a seam it yields on;
//  * bit 3 + k (3-5): CORNER k is an endpoint of a seam edge that a triangle of this triangle's own
//    chart yields on (set on every such triangle, including the one holding the edge): the fan
//    triangles that touch the seam only at a vertex.
//
// Rule: a molecule the triangle owns, with compartment-space centre c and bounding radius r (about its
// origin, MoleculeType.aabb_min.w), is DROPPED iff, with m = r + r_max,
//     dist(c, segment P_k P_{k+1}) < m   for some edge bit k, or
//     |c − P_k| < m                       for some corner bit k,
// r_max = the largest bounding radius over the molecule types of the compartment's membrane tile set
// (Compartment.scales.w when stored, else computed from the set; docs/format.md).
//
// Why it removes the seam overlaps. Let A (centre c, radius r) be a kept molecule of the yielding
// chart and B (centre c', radius r' ≤ r_max) a molecule of the keeping chart. Ownership puts each
// centre's surface point inside its owner triangle (uv_m lies in that triangle's UV triangle).
// (1) A's triangle T holds the seam edge e, B's triangle T' is across it. On a locally flat surface
// with the centres on it (|z| small against the radii, the membrane case), c ∈ T and c' ∈ T' lie in
// the two closed half-planes of the line through e, so the segment c c' meets that line in a point Y.
// When Y lies on e:  |c − c'| ≥ |c − Y| ≥ dist(c, e) ≥ r + r_max ≥ r + r',  so the bounding spheres
// are disjoint and no atom of B reaches A. A convex fold along e (the triangles' dihedral angle
// ≥ 90° on the centres' side) only moves T' away from c's side of the plane through e, so the bound
// holds there too. (2) When Y lies outside e, the pair faces each other around an endpoint V of e
// (or of the next seam edge), across triangles that touch the seam only at V. The edge bits alone
// miss that case (measured: ~10 residual overlaps per cube-sphere without corner bits), so every
// triangle of A's chart at V carries V's corner bit and keeps nothing within m of V. That is a
// sufficient bound when c's distance to the seam is attained at V or the wedge between c's triangle
// and e is at least 90°; for thinner wedges it is not a proof (dist(c, e) can be as small as
// |c − V|·sin of the wedge angle), and tests/shell/seam_rule_test.cpp measures the result on the
// cube-sphere and the RBC with a brute-force overlap check instead. B is kept up to the seam: the
// keeping chart never loses a molecule, so the seam stays covered; the yielding side leaves a band
// about r_max + r − r' wide beyond the keeping side's reach empty. Not covered either: centres far
// below the surface at a sharp fold.
// The margin is compared in float; its rounding (≲ 1e-6 relative) is far below the atoms' slack.
#ifndef NANO_SEAM_H
#define NANO_SEAM_H
#include "shared/placement_common.h"

NANO_BEGIN

// Only these bits of TriangleShell.seam_edges may be set (the validator checks it): 0-2 edges, 3-5 corners.
NANO_CONST uint kSeamEdgeMask = 63u;

// Euclidean distance from p to the closed segment [a, b] (a point if a == b). Å.
NANO_FN float seam_point_segment_distance(NANO_IN(vec3) p, NANO_IN(vec3) a, NANO_IN(vec3) b) {
  NANO_PRECISE vec3 ab = b - a;
  NANO_PRECISE vec3 ap = p - a;
  NANO_PRECISE float len2 = dot(ab, ab);
  NANO_PRECISE float t = 0.0f;
  if (len2 > 0.0f) t = clamp(dot(ap, ab) / len2, 0.0f, 1.0f);
  NANO_PRECISE vec3 d = ap - ab * t;
  return sqrt(dot(d, d));
}

// True iff a molecule owned by the triangle (P0, P1, P2) with centre `centre` (compartment space)
// and bounding radius `radius` is dropped by the seam rule; `seam_edges` the triangle's seam bits
// (edges 0-2, corners 3-5), `max_radius` the tile set's largest bounding radius.
NANO_FN bool seam_drops(uint seam_edges, NANO_IN(vec3) P0, NANO_IN(vec3) P1, NANO_IN(vec3) P2, NANO_IN(vec3) centre,
                        float radius, float max_radius) {
  if ((seam_edges & kSeamEdgeMask) == 0u) return false;
  NANO_PRECISE float margin = radius + max_radius;
  if ((seam_edges & 1u) != 0u && seam_point_segment_distance(centre, P0, P1) < margin) return true;
  if ((seam_edges & 2u) != 0u && seam_point_segment_distance(centre, P1, P2) < margin) return true;
  if ((seam_edges & 4u) != 0u && seam_point_segment_distance(centre, P2, P0) < margin) return true;
  if ((seam_edges & 8u) != 0u && seam_point_segment_distance(centre, P0, P0) < margin) return true;
  if ((seam_edges & 16u) != 0u && seam_point_segment_distance(centre, P1, P1) < margin) return true;
  if ((seam_edges & 32u) != 0u && seam_point_segment_distance(centre, P2, P2) < margin) return true;
  return false;
}

NANO_END
#endif
