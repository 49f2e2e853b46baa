// The mLAS element traced (declared in element.glsl): one query over a membrane slot's Wang-square mLAS
// (runtime/render/levels/membrane.cpp) or a core box's Wang-cube mLAS (levels/core.cpp), each copy
// filtered, placed and numbered on the fly, then its atoms (atoms.glsl). After membrane.glsl and
// core.glsl, whose element queries it calls.
// From render.comp: levels, orders, instances, molecules, meshes, mask_words, render_instances; the
// best hit; count_work; kTwoLevel, kJitter, kClipping.

// Copy m (instance mi) of the element placed and numbered: false when the membrane's ownership,
// seam rule or the baker's list rejects it.
bool place_element_copy(uint inst, Compartment c, RenderCompartment rc, bool membrane, uint tl, ShellWalk w,
                        uint slot_or_box, ElementQuery e, uint m, MoleculeInstance mi, out Affine3 placement,
                        out uvec2 number) {
  if (membrane) {
    // Ownership and the seam rule first: they need only the copy's UV (the same chart_molecule_uv
    // the placement computes, so bit-identical), and they reject most candidates before the
    // placement's normal, frame and rotation are computed.
    float s_over_S = rc.membrane.y;
    vec2 uv_m = chart_molecule_uv(e.g, s_over_S, mi.position.xyz);
    if (!membrane_keeps_copy(w.mt, uv_m, chart_position(w.chart, uv_m), molecules[mi.molecule_type].aabb_min.w)) {
      count_work(NANO_RC_OWNERSHIP_REJECTS);
      return false;
    }
    if (!membrane_copy_listed_shows(membrane_copy_listed(w.mt, membrane_copy_key(slot_or_box, m)), mi.flags)) {
      count_work(NANO_RC_LISTED_REJECTS);
      return false;
    }
    placement = chart_membrane_molecule(w.chart, e.g, s_over_S, c.scales.w, mi.position.xyz, mi.rotation, uv_m);
    number = copy_number_membrane(render_instances[inst].base.xy, tl, c.replication_width * c.replication_height,
                                  slot_or_box, rc.counts.x, m);
  } else {
    placement = core_soluble_molecule(e.box_min, mi.position.xyz, mi.rotation);
    number = copy_number_core(render_instances[inst].base.xy, rc.span.xy, slot_or_box, rc.counts.y, m);
  }
  return true;
}

// The copies of one element on the ray (o, d) (compartment space), placed on the fly: membrane copies
// of replication slot `slot_or_box` (tile `cell.xy` of the area, on [w.t_lo, w.t_hi]) of triangle
// `tl`, or soluble copies of core-grid box `slot_or_box` (grid cell `cell`). The element's mLAS
// holds its Wang square's or cube's molecule boxes. Called twice, `membrane` constant at each call:
// the membrane slots and the core boxes each get their own mLAS and nLAS loops once compiled. One
// shared call compiled 20 % faster but traced 8–13 % slower on lavapipe with the same work per pixel
// (docs/bench/compile.md): the core walk, ~150 boxes a pixel on a cell, then paid for the membrane's
// state. `c` and `rc` are compartment `ci`'s records, read once per µLAS candidate by the caller.
bool trace_element(uint inst, uint ci, Compartment c, RenderCompartment rc, bool membrane, uint tl, ShellWalk w,
                   uint slot_or_box, ivec3 cell, vec3 o, vec3 d) {
  ElementQuery e;
  e.g = vec2(0.0);
  e.box_min = vec3(0.0);
  e.mask = NANO_NO_INDEX;
  if (membrane) {
    uint tile = recipe_cell(c.membrane_recipe, ivec3(cell.xy, 0));
    if (kTwoLevel) return trace_atom_tile(inst, ci, tl, w.mt, w.chart, cell.xy, tile, slot_or_box, o, d);
    membrane_element_query(rc, w, tile, cell.xy, o, d, e);
  } else if (!core_element_query(c, rc, slot_or_box, cell, o, d, e)) {
    return false;
  }
  RenderLevel level = levels[e.entry];
  if (level.count == 0u) return false;
  bool found = false;
  count_work(NANO_RC_MLAS_QUERIES);
  rayQueryEXT q;
  rayQueryInitializeEXT(q, accelerationStructureEXT(level.address), kAabbOnly, 0xFF, e.ot, e.q_lo, e.dt, e.q_hi);
  while (rayQueryProceedEXT(q)) {
    count_work(NANO_RC_MLAS_CANDIDATES);
    uint p = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false));
    if (p >= level.count) continue;
    uint m = orders[level.order_first + p];
    if (!membrane && e.mask != NANO_NO_INDEX && ((mask_words[e.mask + m / 32u] >> (m % 32u)) & 1u) == 0u) {
      count_work(NANO_RC_MASK_REJECTS);
      continue;
    }
    MoleculeInstance mi = instances[e.first + m];
    if (type_hidden(mi.molecule_type)) continue;
    Affine3 placement;
    uvec2 number;
    if (!place_element_copy(inst, c, rc, membrane, tl, w, slot_or_box, e, m, mi, placement, number)) continue;
    // mLAS-level trivial reject: the copy's bounding sphere wholly clipped.
    if (kClipping && clip_removes_whole_ball(placement.translation, molecules[mi.molecule_type].aabb_min.w)) continue;
    if (kJitter) placement = jittered(placement, number);
    if (!trace_molecule(mi.molecule_type, placement, vec3(0.0), o, d, e.q_lo)) continue;
    found = true;
    best.compartment_instance = inst;
    best.element = membrane ? meshes[c.mesh].first_triangle + tl : slot_or_box;
    best.kind = membrane ? 0u : 1u;
    best.cell = membrane ? ivec4(cell.xy, 0, 0) : ivec4(cell, 0);
    best.instance = m;
    best.copy_number_lo = number.x;
    best.copy_number_hi = number.y;
    if (best_t >= e.q_lo) rayQueryGenerateIntersectionEXT(q, best_t);  // a hit must lie in the query's range
  }
  return found;
}
