// Ray–AABB slab test and 3D-DDA over a uniform grid (Amanatides & Woo; ALGORITHMS.md §4–5) for the
// core renderer's walk over core-grid boxes. GLSL 460 and C++20/GLM. Rays: o + t·d, d NOT normalised.
#ifndef NANO_GRID_DDA_H
#define NANO_GRID_DDA_H
#include "shared/placement_common.h"

NANO_BEGIN

// Slab test of ray o + t·d against the closed box [lo, hi] restricted to [t0, t1].
// Never produces NaN: an axis whose 1/d is infinite (d = ±0 or subnormal) is treated as parallel
// (inside iff lo ≤ o ≤ hi on that axis), so 0·∞ never occurs. Each slab's far t is widened by
// 2γ₃·|t| (Ize 2013) so a ray through an edge or corner is not lost to rounding.
// On true, t_near ≤ t_far is the (slightly conservative) overlap; on false the values are unspecified.
NANO_FN bool aabb_intersect(NANO_IN(vec3) lo, NANO_IN(vec3) hi, NANO_IN(vec3) o, NANO_IN(vec3) d, float t0,
                    float t1, NANO_OUT(float) t_near, NANO_OUT(float) t_far) {
  t_near = t0;
  t_far = t1;
  for (int i = 0; i < 3; ++i) {
    float inv = 1.0f / d[i];
    if (!(abs(inv) <= placement_flt_max())) {
      if (o[i] < lo[i] || o[i] > hi[i]) return false;
      continue;
    }
    float ta = (lo[i] - o[i]) * inv;
    float tb = (hi[i] - o[i]) * inv;
    float tn = min(ta, tb);
    float tf = max(ta, tb);
    tf = tf + 2.0f * kPlacementGamma3 * abs(tf);
    t_near = max(t_near, tn);
    t_far = min(t_far, tf);
  }
  return t_near <= t_far;
}

// Iterator over the cells of a uniform grid of res.x × res.y × res.z cells of size cell_size, minimum
// corner grid_min, pierced by the ray segment [t0, t1]. Usage (both languages):
//   GridDda it; dda_init(it, grid_min, cell_size, res, o, d, t0, t1);
//   ivec3 cell; float ta; float tb;
//   while (dda_next(it, cell, ta, tb)) { ... visit cell over [ta, tb] ... }
// Cells come in ray order, each once, 6-connected (one axis steps at a time; when the ray crosses an
// edge or corner exactly, the intermediate cells it only touches are visited too).
struct GridDda {
  vec3 org;          // ray origin in grid units ((o − grid_min) / cell_size)
  vec3 dir;          // ray direction in grid units (d / cell_size); t is the world t
  ivec3 res;
  ivec3 cell;        // current cell
  ivec3 step;        // +1 / −1 / 0 per axis (0 for d = ±0)
  vec3 t_delta;      // 1 / |dir| per axis, +∞ for a zero component (informational)
  float t_cur;       // entry t of the current cell
  float t_end;       // end of the clipped segment
  int steps_left;    // safety cap Σres + 3
  bool running;
};

// Next boundary crossing on axis i of the current cell, recomputed from the cell index (no drift).
NANO_FN float dda_next_crossing(NANO_IN(GridDda) it, int i) {
  if (it.step[i] == 0) return placement_inf();
  float plane = float(it.step[i] > 0 ? it.cell[i] + 1 : it.cell[i]);
  return (plane - it.org[i]) / it.dir[i];
}

// Initialises the iterator: clips [t0, t1] to the grid box with aabb_intersect, then takes the cell
// of the entry point, clamp(floor(p), 0, res − 1). Inactive if the segment misses the grid or res has a
// zero component. grid_min, cell_size in Å (cell_size > 0), res ≥ 0.
NANO_FN void dda_init(NANO_OUT(GridDda) it, NANO_IN(vec3) grid_min, NANO_IN(vec3) cell_size, NANO_IN(ivec3) res,
              NANO_IN(vec3) o, NANO_IN(vec3) d, float t0, float t1) {
  it.org = (o - grid_min) / cell_size;
  it.dir = d / cell_size;
  it.res = res;
  it.cell = ivec3(0);
  it.step = ivec3(0);
  it.t_delta = vec3(placement_inf());
  it.t_cur = t0;
  it.t_end = t1;
  it.steps_left = res.x + res.y + res.z + 3;
  it.running = false;
  if (res.x <= 0 || res.y <= 0 || res.z <= 0) return;
  float tn; float tf;
  if (!aabb_intersect(vec3(0.0f), vec3(res), it.org, it.dir, t0, t1, tn, tf)) return;
  it.t_cur = tn;
  it.t_end = min(tf, t1);
  vec3 p = it.org + tn * it.dir;
  it.cell = clamp(ivec3(floor(p)), ivec3(0), res - ivec3(1));
  for (int i = 0; i < 3; ++i) {
    float a = abs(it.dir[i]);  // abs turns −0 into +0
    it.step[i] = it.dir[i] > 0.0f ? 1 : (it.dir[i] < 0.0f ? -1 : 0);
    if (!(1.0f / a <= placement_flt_max())) it.step[i] = 0;  // subnormal/zero: parallel
    it.t_delta[i] = it.step[i] == 0 ? placement_inf() : 1.0f / a;
  }
  it.running = true;
}

// Moves the walk from its current cell to the neighbour across the nearest boundary (ends it when
// that boundary lies beyond the segment or the neighbour is outside the grid); returns the t where
// the current cell is left, clipped to [t_cur, t_end].
NANO_FN float dda_advance(NANO_INOUT(GridDda) it) {
  float tx = dda_next_crossing(it, 0);
  float ty = dda_next_crossing(it, 1);
  float tz = dda_next_crossing(it, 2);
  int axis = 0;
  float tnext = tx;
  if (ty < tnext) { axis = 1; tnext = ty; }
  if (tz < tnext) { axis = 2; tnext = tz; }
  float t_exit = min(max(tnext, it.t_cur), it.t_end);
  if (tnext > it.t_end) {
    it.running = false;  // this was the last cell
  } else {
    it.cell[axis] += it.step[axis];
    it.t_cur = t_exit;
    if (it.cell[axis] < 0 || it.cell[axis] >= it.res[axis]) it.running = false;
  }
  return t_exit;
}

// The current cell of a running walk and the t where the ray entered it; false when the walk is over.
// Each true return counts against the safety cap: a loop of dda_current … dda_advance visits at most
// Σres + 3 cells.
NANO_FN bool dda_current(NANO_INOUT(GridDda) it, NANO_OUT(ivec3) cell, NANO_OUT(float) t_enter) {
  cell = it.cell;
  t_enter = it.t_cur;
  if (!it.running || it.steps_left <= 0) return false;
  it.steps_left -= 1;
  return true;
}

// Returns false when the walk is over. Otherwise reports the current cell and its t range
// [t_enter, t_exit] (clipped to the segment; t_exit may equal t_enter for a cell that is only
// touched), then advances to the neighbour across the nearest boundary.
NANO_FN bool dda_next(NANO_INOUT(GridDda) it, NANO_OUT(ivec3) cell, NANO_OUT(float) t_enter, NANO_OUT(float) t_exit) {
  t_exit = it.t_cur;
  if (!dda_current(it, cell, t_enter)) return false;
  t_exit = dda_advance(it);
  return true;
}

// Empty-space skipping: the current cell (from dda_current) lies in the block of cells
// [block_lo, block_hi] (inclusive) where nothing is to be found. Moves the walk to the ray's last
// cell in the block, so that the next dda_advance leaves the block as if the walk had stepped cell
// by cell; ends the walk when the segment ends inside the block. The last cell is taken where the
// ray leaves the block's box, clamped into the block and never behind the current cell on any axis
// (so rounding can neither leave the block early nor walk backwards: every skip moves the walk
// forward), and the dda_advance from it crosses the boundary the ray really crosses first.
NANO_FN void dda_skip_block(NANO_INOUT(GridDda) it, NANO_IN(ivec3) block_lo, NANO_IN(ivec3) block_hi) {
  float t_leave = placement_inf();
  ivec3 last = it.cell;
  for (int i = 0; i < 3; ++i) {
    if (it.step[i] == 0) continue;
    float plane = float(it.step[i] > 0 ? block_hi[i] + 1 : block_lo[i]);
    t_leave = min(t_leave, (plane - it.org[i]) / it.dir[i]);
  }
  if (!(t_leave <= it.t_end)) {  // the segment ends inside the block (or the ray never leaves it)
    it.running = false;
    return;
  }
  vec3 p = clamp(floor(it.org + max(t_leave, it.t_cur) * it.dir), vec3(block_lo), vec3(block_hi));
  for (int i = 0; i < 3; ++i) {
    if (it.step[i] > 0) last[i] = max(last[i], int(p[i]));
    if (it.step[i] < 0) last[i] = min(last[i], int(p[i]));
  }
  it.cell = last;
}

NANO_END
#endif
