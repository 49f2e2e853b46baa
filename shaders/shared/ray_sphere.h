// Ray–sphere intersection in the numerically careful form of Ray Tracing Gems ch. 7 (Haines et al.):
// the discriminant from the perpendicular distance of the centre to the line, and the two roots
// from q = −(β + sign(β)·√Δ) so neither suffers cancellation. GLSL 460 and C++20/GLM.
#ifndef NANO_RAY_SPHERE_H
#define NANO_RAY_SPHERE_H
#include "shared/placement_common.h"

NANO_BEGIN

// Ray o + t·d (d any non-zero length, NOT normalised; t in units of d) against the sphere of centre
// `centre` and radius r (Å). On true, t_near ≤ t_far are both roots of |o + t d − centre| = r over
// all real t (either may be negative: the caller clips to its [t_min, t_max]). False if the line
// misses (perpendicular distance > r) or d = 0. Relative error of each root: a few float ulps of
// max(|t|, r/|d|) away from tangency; intersect in molecule space for atoms (ALGORITHMS.md §5).
NANO_FN bool sphere_intersect(NANO_IN(vec3) o, NANO_IN(vec3) d, NANO_IN(vec3) centre, float r,
                      NANO_OUT(float) t_near, NANO_OUT(float) t_far) {
  t_near = 0.0f;
  t_far = 0.0f;
  vec3 f = o - centre;
  float a = dot(d, d);
  if (!(a > 0.0f)) return false;
  float beta = dot(f, d);                 // half of the textbook b
  vec3 l = f - (beta / a) * d;            // centre → closest point of the line
  float dist = length(l);
  if (dist > r) return false;
  float disc = a * ((r - dist) * (r + dist));  // β² − a·c without cancellation
  float c = dot(f, f) - r * r;
  float q = -(beta + (beta >= 0.0f ? sqrt(disc) : -sqrt(disc)));
  float ta;
  float tb;
  if (q != 0.0f) {
    ta = c / q;
    tb = q / a;
  } else {  // β = 0 and Δ = 0: tangent at the foot of the perpendicular
    ta = -beta / a;
    tb = ta;
  }
  t_near = min(ta, tb);
  t_far = max(ta, tb);
  return true;
}

NANO_END
#endif
