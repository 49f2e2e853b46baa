// The UV-seam rule (ALGORITHMS.md §1, "UV seams read unrelated recipe regions"): across a mesh edge
// whose two triangles do not share the edge's UVs, the two triangles map unrelated regions of the
// Wang tiling, so molecules of both sides can overlap in space. BOTH sides of a seam keep their
// molecules clear of it: each drops the copies whose bounding sphere reaches the seam.
// GLSL 460 and C++20/GLM (glsl_cpp.h); the baker's enumerator (bake/shell/membrane_mapping.hpp), the
// explicit-instancing oracle (runtime/oracle) and the shader call this same function on the same
// floats, so all three drop exactly the same copies.
//
// Bits of TriangleShell.seam_edges (all others zero; the validator checks it):
//  * bit k (0-2): EDGE k of the triangle, between its corners k and (k + 1) mod 3 (edge 0: corners
//    0–1, edge 1: 1–2, edge 2: 2–0; corner order of the "triangles" section), is a seam (set on both
//    triangles of the edge);
//  * bit 3 + k (3-5): CORNER k is an endpoint of a seam edge and the triangle holds no seam edge
//    through it: the fan triangles that touch a seam only at a vertex.
//
// Rule: a molecule the triangle owns, with surface point X = chart_position(uv_m) (on the flat
// triangle, where its centre stands before the lift z along the normal) and bounding radius r (about
// its origin, MoleculeType.aabb_min.w), is DROPPED iff
//     dist(X, segment P_k P_{k+1}) < r   for some edge bit k, or
//     |X − P_k| < 2r                      for some corner bit k.
//
// Why it removes the seam overlaps. Let A (surface point X, radius r) and B (X', r') be kept
// molecules of triangles T and T' on the two sides of a seam edge e. Ownership puts X in T and X' in
// T'. On a locally flat surface X and X' lie in the two closed half-planes of the line through e, so
// the segment X X' meets that line in a point Y. When Y lies on e:
//     |X − X'| = |X − Y| + |Y − X'| ≥ dist(X, e) + dist(X', e) ≥ r + r'.
// The centres are X + z·n and X' + z'·n' with n ≈ n': the lifts are (nearly) normal to X − X', so
// |c − c'| ≥ |X − X'| ≥ r + r' up to the normals' turn (a relative κ·|z|, 3% for the virion's lipids),
// and no atom of B reaches A. The distance is taken on the surface points, not the centres: a centre
// lifted 12 Å (a lipid's leaflet) is 3D-far from the edge while laterally close to it. A convex
// fold along e only moves T' away from X's side. When Y lies outside e, the pair faces each other
// around an endpoint V of e (or of the next seam edge) from fan triangles that touch the seam only
// at V. Their corner bits keep X at least 2r from V; with X seen from V at an angle φ from the
// nearest seam edge, dist(X, seam) ≥ 2r·sin φ ≥ r when φ ≥ 30° — true when the seam-holding
// triangles' angles at V are at least 30°, which the bundled meshes have (a measured 2r, not a
// proof for every mesh): tests/shell/seam_rule_test.cpp counts overlaps on the cube-sphere and the
// RBC by brute force, and the bake tests check whole packages for atom clashes (the corner margin r
// let two lipids 16 Å apart meet across a cube corner of the virion). Each side loses only a band of
// its own molecules' radius (an earlier one-sided rule, one side dropping within r + r_max, cost the
// virion a third of its membrane copies).
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

// True iff a molecule owned by the triangle (P0, P1, P2) with surface point `surface`
// (chart_position(uv_m), compartment space) and bounding radius `radius` is dropped by the seam
// rule; `seam_edges` the triangle's seam bits (edges 0-2, corners 3-5).
NANO_FN bool seam_drops(uint seam_edges, NANO_IN(vec3) P0, NANO_IN(vec3) P1, NANO_IN(vec3) P2, NANO_IN(vec3) surface,
                        float radius) {
  if ((seam_edges & kSeamEdgeMask) == 0u) return false;
  NANO_PRECISE float margin = radius;
  NANO_PRECISE float corner_margin = 2.0f * radius;
  if ((seam_edges & 1u) != 0u && seam_point_segment_distance(surface, P0, P1) < margin) return true;
  if ((seam_edges & 2u) != 0u && seam_point_segment_distance(surface, P1, P2) < margin) return true;
  if ((seam_edges & 4u) != 0u && seam_point_segment_distance(surface, P2, P0) < margin) return true;
  if ((seam_edges & 8u) != 0u && seam_point_segment_distance(surface, P0, P0) < corner_margin) return true;
  if ((seam_edges & 16u) != 0u && seam_point_segment_distance(surface, P1, P1) < corner_margin) return true;
  if ((seam_edges & 32u) != 0u && seam_point_segment_distance(surface, P2, P2) < corner_margin) return true;
  return false;
}

NANO_END
#endif
