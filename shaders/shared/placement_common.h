// Small shared helpers of the placement math (GLSL 460 and C++20/GLM, see glsl_cpp.h).
// Everything here is in Ångström where a length is involved; rays are o + t·d with d NOT
// normalised, so one t is shared by every level of the nested traversal.
#ifndef NANO_PLACEMENT_COMMON_H
#define NANO_PLACEMENT_COMMON_H
#include "shared/glsl_cpp.h"

NANO_BEGIN

// Machine epsilon of float as used by pbrt: 2^-24.
NANO_CONST float kPlacementMachineEps = 5.9604644775390625e-8f;
// gamma_3 = 3·eps / (1 − 3·eps) (Higham), used to widen slab t_max (Ize 2013).
NANO_CONST float kPlacementGamma3 = 1.78813947e-7f;

// +infinity (IEEE), identical on both sides.
NANO_FN float placement_inf() { return uintBitsToFloat(0x7F800000u); }
// Largest finite float.
NANO_FN float placement_flt_max() { return uintBitsToFloat(0x7F7FFFFFu); }

// A 3×4 affine transform x ↦ linear·x + translation (the linear part is a column-major mat3,
// exactly like GLSL and GLM). Used for M1, the composed molecule transform and instance transforms.
struct Affine3 {
  mat3 linear;
  vec3 translation;
};

// Returns linear·p + translation (a point).
NANO_FN vec3 affine_point(NANO_IN(Affine3) m, NANO_IN(vec3) p) { return m.linear * p + m.translation; }
// Returns linear·v (a direction; NOT normalised, so t is preserved).
NANO_FN vec3 affine_vector(NANO_IN(Affine3) m, NANO_IN(vec3) v) { return m.linear * v; }
// Composition a∘b: x ↦ a(b(x)).
NANO_FN Affine3 affine_compose(NANO_IN(Affine3) a, NANO_IN(Affine3) b) {
  Affine3 r;
  r.linear = a.linear * b.linear;
  r.translation = a.linear * b.translation + a.translation;
  return r;
}
// Affine transform whose linear part is a rotation R (orthonormal, det +1): inverse is Rᵀ.
// Returns the ray (o, d) expressed in the local frame: o' = Rᵀ(o − translation), d' = Rᵀd.
// The ray parameter t is unchanged (d is not normalised).
NANO_FN void affine_rigid_inverse_ray(NANO_IN(Affine3) m, NANO_IN(vec3) o, NANO_IN(vec3) d,
                              NANO_OUT(vec3) o_local, NANO_OUT(vec3) d_local) {
  mat3 rt = transpose(m.linear);
  o_local = rt * (o - m.translation);
  d_local = rt * d;
}

NANO_END
#endif
