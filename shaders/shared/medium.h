// The medium between compartment instances (scene.json "medium", docs/scene.md#medium): a soluble
// whose Wang cubes tile a world-space region virtually (a periodic recipe, nothing stored per box)
// and whose copies are kept only where each compartment instance's exclusion field leaves room.
// The shader and the CPU oracle (runtime/placement/) decide every copy with these functions.
#ifndef NANO_MEDIUM_H
#define NANO_MEDIUM_H

#include "glsl_cpp.h"

NANO_BEGIN

// Section "exclusion_fields": one record per compartment (parallel to "compartments"). A grid of
// nodes in compartment space holding, per node, how far it stands clear of everything the
// compartment draws, clamped to ±limits.y: outside the mesh the least, over its triangles, of the
// distance to the triangle less how far that triangle's membrane copies reach from it; inside,
// minus the distance less the largest reach. Between nodes the field is trilinear;
// limits.x, measured by the baker where the field matters, covers what interpolation overstates.
// A point beyond the grid is clear: the grid spans the mesh grown by every reach the medium needs.
struct ExclusionField {
  vec4 origin;  // xyz: compartment-space position of node (0, 0, 0); w: node spacing (Å, > 0)
  uvec4 dims;   // xyz: nodes per axis (≥ 2 each); w: first value in section "exclusion_values"
  vec4 limits;  // x: margin subtracted from every interpolated value (Å, ≥ 0); y: clamp (Å, > 0);
                // z: 1 / spacing as a float division gives it (a multiplication decides alike on
                // every device: GLSL may divide to 2.5 ulp); w: reserved
};

// Section "medium": no record, or exactly one. The region's boxes are (i, j, k) with corner
// region_min + (i, j, k)·B; box (i, j, k) holds the cube the recipe gives cell (i, j, k) (recipes
// wrap). A copy is drawn iff medium_copy_clear holds for every instance whose field reaches it.
struct Medium {
  vec4 region_min;  // xyz: world minimum of the region (Å); w: box edge B (the soluble's cube size)
  vec4 region_max;  // xyz: world maximum (region_min + boxes·B ≥ the scene's region); w: clearance (Å)
  uvec4 boxes;      // xyz: boxes per axis; w: the 3D recipe (index into "recipes")
  uvec4 tiles;      // x: first cube (index into "tiles3d"); y: cube count; z: largest instance
                    // count I of those cubes; w: reserved
};

// What the renderer and the CPU oracle derive for each compartment instance (runtime/placement/
// medium_instances.hpp): the affine map from region space (world − region_min) to the instance's
// compartment space, row-major, and the least factor by which the instance's linear part stretches.
struct MediumInstance {
  vec4 row0;      // compartment = (row0·(p, 1), row1·(p, 1), row2·(p, 1)) for region-space p
  vec4 row1;
  vec4 row2;
  vec4 stretch;   // x: least singular value of the instance's linear part; yzw: reserved
  uvec4 ids;      // x: compartment (its exclusion field); yzw: reserved
};

// Per frame (GpuScene::set_eye): the box holding the eye and the eye within it as an unevaluated sum
// of floats, so the walk traces in eye-box space (box (i, j, k) at (ijk − eye_box)·B: small numbers
// near the eye, wherever the region lies); where the medium's copy numbers start; and the cube-space
// box that holds every medium copy's sphere.
struct RenderMedium {
  ivec4 eye_box;  // xyz: the box (i, j, k) of the eye (may lie outside the region); w: reserved
  vec4 eye_hi;    // xyz: float(eye − region_min − eye_box·B); w: reserved
  vec4 eye_lo;    // xyz: the rest
  uvec4 numbers;  // xy: first copy number of the medium (lo, hi); z: instances with a field; w: reserved
  vec4 reach_lo;  // xyz: cube-space minimum of every medium molecule's bounding sphere (≥ −B)
  vec4 reach_hi;  // xyz: cube-space maximum (≤ 2B)
};

// PixelHit.compartment_instance of a medium copy (kind NANO_KIND_MEDIUM): it belongs to no instance.
NANO_CONST uint NANO_MEDIUM_OWNER = 0xFFFFFFFEu;
NANO_CONST uint NANO_KIND_MEDIUM = 2u;

// The keep rule must decide alike on the device and in the oracle: its arithmetic is written out
// operation by operation and `precise` in GLSL, so no compiler fuses or reorders it (C++ on x86-64
// without -mfma fuses nothing either).
NANO_FN float medium_row(NANO_IN(vec4) r, NANO_IN(vec3) p) {
  NANO_PRECISE float s = r.x * p.x;
  s = s + r.y * p.y;
  s = s + r.z * p.z;
  return s + r.w;
}

// Region space to compartment space by an instance's record.
NANO_FN vec3 medium_to_compartment(NANO_IN(MediumInstance) m, NANO_IN(vec3) p) {
  return vec3(medium_row(m.row0, p), medium_row(m.row1, p), medium_row(m.row2, p));
}

NANO_FN float medium_lerp(float a, float b, float t) {
  NANO_PRECISE float d = b - a;
  NANO_PRECISE float r = a + t * d;
  return r;
}

// Where compartment-space point p falls among the field's nodes: the cell (its lowest node) and
// the fraction within it. False beyond the grid, where the field is clear.
NANO_FN bool exclusion_cell(NANO_IN(ExclusionField) f, NANO_IN(vec3) p, NANO_OUT(ivec3) cell, NANO_OUT(vec3) frac) {
  NANO_PRECISE vec3 g = (p - vec3(f.origin)) * f.limits.z;
  vec3 top = vec3(ivec3(f.dims) - ivec3(1));
  cell = ivec3(0);
  frac = vec3(0.0f);
  if (!(g.x >= 0.0f && g.y >= 0.0f && g.z >= 0.0f && g.x <= top.x && g.y <= top.y && g.z <= top.z)) return false;
  cell = min(ivec3(floor(g)), ivec3(f.dims) - ivec3(2));
  frac = g - vec3(cell);
  return true;
}

// Index in "exclusion_values" of node n.
NANO_FN uint exclusion_node(NANO_IN(ExclusionField) f, NANO_IN(ivec3) n) {
  return f.dims.w + uint(n.x) + f.dims.x * (uint(n.y) + f.dims.y * uint(n.z));
}

// The trilinear value of a cell's corners c[x + 2y + 4z] at fraction t.
NANO_FN float exclusion_trilinear(float c[8], NANO_IN(vec3) t) {
  float x00 = medium_lerp(c[0], c[1], t.x);
  float x10 = medium_lerp(c[2], c[3], t.x);
  float x01 = medium_lerp(c[4], c[5], t.x);
  float x11 = medium_lerp(c[6], c[7], t.x);
  return medium_lerp(medium_lerp(x00, x10, t.y), medium_lerp(x01, x11, t.y), t.z);
}

// A copy whose bounding sphere has world radius r keeps the medium's clearance from one instance:
// the field's value at its centre (compartment space), less the field's margin, scaled by the
// instance's least stretch (world Å per compartment Å), is at least r + clearance.
NANO_FN bool medium_copy_clear(float field_value, NANO_IN(ExclusionField) f, float least_stretch, float radius,
                               float clearance) {
  NANO_PRECISE float room = (field_value - f.limits.x) * least_stretch;
  NANO_PRECISE float needed = radius + clearance;
  return room >= needed;
}

// The centre of copy m of box ijk in region space (world − region_min): how the renderer and the
// oracle both place it before testing it (the cube's position of the molecule's origin, Å).
NANO_FN vec3 medium_copy_centre(NANO_IN(ivec3) ijk, float B, NANO_IN(vec3) position_in_cube) {
  return vec3(ijk) * B + position_in_cube;
}

NANO_END

#ifdef __cplusplus
static_assert(sizeof(nano::gpu::ExclusionField) == 48);
static_assert(sizeof(nano::gpu::Medium) == 64);
static_assert(sizeof(nano::gpu::MediumInstance) == 80);
static_assert(sizeof(nano::gpu::RenderMedium) == 96);
#endif
#endif
