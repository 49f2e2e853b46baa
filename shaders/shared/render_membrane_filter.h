// Which membrane copies a triangle renders (docs/placement.md step 4). Every rule that rejects a
// candidate copy of a triangle lives in this one function, so a new rule (a per-instance distortion
// limit, say) is added here once and the shader and any C++ caller follow. GLSL 460 and C++20/GLM.
#ifndef NANO_RENDER_MEMBRANE_FILTER_H
#define NANO_RENDER_MEMBRANE_FILTER_H
#include "shared/ownership.h"
#include "shared/package_records.h"
#include "shared/seam.h"

NANO_BEGIN

// The triangle's corners (compartment space), UVs and seam bits, as docs/placement.md reads them.
struct MembraneTriangle {
  vec3 p0;
  vec3 p1;
  vec3 p2;
  vec2 t0;
  vec2 t1;
  vec2 t2;
  uint seam_edges;     // TriangleShell.seam_edges (0 without triangle_shells)
  uint drop_first;     // TriangleDrops of the triangle: its dropped copies' keys (count 0 without drops)
  uint drop_count;
};

// The key of a membrane copy among its triangle's dropped copies (package_records.h, TriangleDrops):
// replication slot sx + W·sy and instance index in the slot's Wang square.
NANO_FN uint membrane_copy_key(uint slot, uint instance) { return (slot << NANO_DROP_INSTANCE_BITS) | instance; }

// Whether the baker dropped the copy is the last test (a binary search over the triangle's keys in
// section dropped_copies): the shader and the oracle each search their own copy of the section.
// True iff the triangle keeps the copy whose molecule UV is uv_m, surface point `surface`
// (chart_position(chart, uv_m)) and bounding radius `radius` (MoleculeType.aabb_min.w): it owns uv_m
// and the seam rule keeps it.
NANO_FN bool membrane_keeps_copy(NANO_IN(MembraneTriangle) tri, NANO_IN(vec2) uv_m, NANO_IN(vec3) surface, float radius) {
  if (!own_triangle_owns(tri.t0, tri.t1, tri.t2, uv_m)) return false;
  return !seam_drops(tri.seam_edges, tri.p0, tri.p1, tri.p2, surface, radius);
}

// Whether a copy the triangle owns is shown, given whether its key is among the triangle's listed
// keys (section dropped_copies): a listed instance is dropped, a listed alternate shown instead.
NANO_FN bool membrane_copy_listed_shows(bool listed, uint instance_flags) {
  return listed == ((instance_flags & NANO_INSTANCE_ALTERNATE) != 0u);
}

NANO_END
#endif
