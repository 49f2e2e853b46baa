// The core grid: a compartment's soluble copies by a 3D-DDA over its boxes (skip levels leap empty
// blocks), each box by its occupancy and keep-mask, then its Wang cube's mLAS query. Built by
// runtime/render/levels/core.cpp (cube mLASes, kept boxes); occupancy, boundary boxes and skip levels
// are sections (levels/sections.cpp).
// From render.comp: occupancy_words, boundary_boxes, kept_boxes, core_skip_words, cubes, frame,
// best_t; count_work; kClipping.

uint occupancy_of(uint byte_index) { return (occupancy_words[byte_index >> 2] >> (8u * (byte_index & 3u))) & 0xFFu; }

// The record of BOUNDARY box `box` in boundary_boxes and kept_boxes (binary search over the
// compartment's sorted records), or NANO_NO_INDEX when the package lists none (the validator makes
// that impossible).
uint boundary_record(Compartment c, uint box) {
  uint lo = c.core_masks.x;
  uint hi = c.core_masks.x + c.core_masks.y;
  while (lo < hi) {
    uint mid = (lo + hi) >> 1;
    if (boundary_boxes[mid].box < box) lo = mid + 1u; else hi = mid;
  }
  if (lo < c.core_masks.x + c.core_masks.y && lo < uint(kept_boxes.length()) && boundary_boxes[lo].box == box) return lo;
  return NANO_NO_INDEX;
}

// Core-grid box `box` (grid cell `cell`): false when the ray misses what the box can hold, clipping
// removes it or it lies outside the compartment.
bool core_element_query(Compartment c, RenderCompartment rc, uint box, ivec3 cell, vec3 o, vec3 d, inout ElementQuery e) {
  uint occ = occupancy_of(c.grid_dims.w + box);
  if (occ == NANO_BOX_OUTSIDE) return false;
  e.box_min = core_box_min(c.grid_min.xyz, vec3(c.grid_min.w), cell);
  float tn;
  float tf;
  if (!aabb_intersect(e.box_min + rc.reach_lo.xyz, e.box_min + rc.reach_hi.xyz, o, d, 0.0, best_t, tn, tf)) return false;
  if (kClipping && clip_removes_box(e.box_min + rc.reach_lo.xyz, e.box_min + rc.reach_hi.xyz)) return false;
  if (occ == NANO_BOX_BOUNDARY) {
    uint record = boundary_record(c, box);
    if (record == NANO_NO_INDEX) return false;
    vec3 kept_lo;
    vec3 kept_hi;
    if (!kept_box_unpack(kept_boxes[record], c.grid_min.w, kept_lo, kept_hi) ||
        !aabb_intersect(e.box_min + kept_lo, e.box_min + kept_hi, o, d, 0.0, best_t, tn, tf))
      return false;
    e.mask = boundary_boxes[record].first_word;
  }
  uint cube = recipe_cell(c.soluble_recipe, cell);
  e.entry = frame.levels.y + cube;
  e.first = cubes[cube].first_instance;
  e.ot = o - e.box_min;
  e.dt = d;
  e.q_lo = 0.0;
  e.q_hi = best_t;
  return true;
}

// The soluble copies of instance `inst`'s core grid (compartment `ci`) on the ray (o, od): its own
// walk (its own mLAS and nLAS loops once compiled), cells in ray order, at each the boxes within one
// step not traced at the cell before. False when it found no nearer hit.
bool trace_core_grid(uint inst, uint ci, Compartment c, RenderCompartment rc, vec3 o, vec3 od) {
  if (rc.span.z == 0u) return false;
  float B = c.grid_min.w;
  if (kClipping && clip_removes_box(c.grid_min.xyz - vec3(B), c.grid_min.xyz + vec3(ivec3(c.grid_dims.xyz) + ivec3(1)) * B)) return false;
  // The grid widened by one box on every side: a molecule reaches at most one box beyond its own,
  // so every point where a copy can be hit lies in a cell of this grid within one step of its box.
  GridDda it;
  dda_init(it, c.grid_min.xyz - vec3(B), vec3(B), ivec3(c.grid_dims.xyz) + ivec3(2), o, od, 0.0, best_t);
  ShellWalk w;  // trace_element's membrane state, unused by a core box
  bool found = false;
  ivec3 dims = ivec3(c.grid_dims.xyz);
  ivec3 cell;
  float ta;
  ivec3 previous = ivec3(-1000000);
  ivec3 cells = dims + ivec3(2);
  while (dda_current(it, cell, ta)) {
    if (ta > best_t) break;  // a cell beyond the best hit ends the walk
    count_work(NANO_RC_CORE_STEPS);
    uint skip_index = rc.core_skip.x + uint(cell.x) + uint(cells.x) * (uint(cell.y) + uint(cells.y) * uint(cell.z));
    uint skip = core_skip_level_in_word(core_skip_words[skip_index >> 3], skip_index);
    if (skip != 0u) {
      // Nothing to trace within one step of any cell of the block: the walk resumes beyond it.
      // `cell`'s own boxes are dead, so it may stand as the cell before for the de-duplication.
      ivec3 block_lo = core_skip_block_lo(cell, skip);
      dda_skip_block(it, block_lo, core_skip_block_hi(block_lo, skip, cells));
    } else {
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            ivec3 ijk = cell - ivec3(1) + ivec3(dx, dy, dz);
            if (any(lessThan(ijk, ivec3(0))) || any(greaterThanEqual(ijk, dims))) continue;
            ivec3 from_previous = abs(ijk - (previous - ivec3(1)));
            if (max(from_previous.x, max(from_previous.y, from_previous.z)) <= 1) continue;
            count_work(NANO_RC_CORE_BOXES);
            uint box = uint(ijk.x) + uint(dims.x) * (uint(ijk.y) + uint(dims.y) * uint(ijk.z));
            if (trace_element(inst, ci, c, rc, false, 0u, w, box, ijk, o, od)) found = true;
          }
    }
    previous = cell;
    dda_advance(it);  // the one step of the walk, after a skip out of the block
  }
  return found;
}
