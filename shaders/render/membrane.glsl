// The membrane shell: a µLAS prism's walk over its triangle's replication area (each slot's box, or
// the area's repLAS query), each slot's Wang-square mLAS query, and the two-level membrane (--levels
// 2: a square's atom BLAS). Built by runtime/render/levels/membrane.cpp (prisms' offsets, square
// mLASes, repLAS, atom BLASes); the triangles' drop lists are sections (levels/sections.cpp).
// From render.comp: meshes, positions, normals, uvs, triangles, shells, triangle_drops,
// dropped_copies, compartments, render_compartments, render_instances, squares, instances, molecules,
// atoms, levels, orders, frame; the best hit; count_work; kExactPrism, kReplicationLas, kLargeAreas,
// kRepLasWalk, kTwoLevel, kJitter, kClipping.

// True iff the baker listed the copy `key` (membrane_copy_key) of the triangle (dropped, or an
// alternate shown): binary search over its strictly ascending keys (the validator checks the order
// and the range).
bool membrane_copy_listed(MembraneTriangle mt, uint key) {
  uint lo = mt.drop_first;
  uint hi = mt.drop_first + mt.drop_count;
  while (lo < hi) {
    uint mid = (lo + hi) >> 1;
    if (dropped_copies[mid] < key) lo = mid + 1u; else hi = mid;
  }
  return lo < mt.drop_first + mt.drop_count && dropped_copies[lo] == key;
}

// Two-level membrane tile: atoms straight from the square's atom BLAS, intersected as spheres in tile
// space (ellipsoids in the world under M1's stretch and shear), with the molecule's ownership and seam
// rule decided at its true centre.
bool trace_atom_tile(uint inst, uint ci, uint tl, MembraneTriangle mt, TriangleChart chart, ivec2 cell, uint tile,
                     uint slot, vec3 o, vec3 d) {
  Compartment c = compartments[ci];
  RenderCompartment rc = render_compartments[ci];
  RenderLevel level = levels[frame.levels.w + tile];
  if (level.count == 0u) return false;
  float s_over_S = rc.membrane.y;
  vec2 g = replication_tile_uv(cell, rc.membrane.x);
  vec3 ot;
  vec3 dt;
  chart_tile_inverse_ray(chart, g, s_over_S, o, d, ot, dt);
  uint first = squares[tile].first_instance;
  bool found = false;
  count_work(NANO_RC_NLAS_QUERIES);
  rayQueryEXT q;
  rayQueryInitializeEXT(q, accelerationStructureEXT(level.address), kAabbOnly, 0xFF, ot, 0.0, dt, best_t);
  while (rayQueryProceedEXT(q)) {
    count_work(NANO_RC_NLAS_CANDIDATES);
    uint p = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false));
    if (p >= level.count) continue;
    uint m = orders[level.order_first + 2u * p];
    uint a = orders[level.order_first + 2u * p + 1u];
    MoleculeInstance mi = instances[first + m];
    if (type_hidden(mi.molecule_type)) continue;
    vec4 cr = atoms[a].centre_radius;
    vec3 centre = mi.position.xyz + quat_rotate(mi.rotation, cr.xyz);
    float tn;
    float tf;
    count_work(NANO_RC_SPHERE_TESTS);
    if (!sphere_intersect(ot, dt, centre, cr.w, tn, tf)) continue;
    float t = tn >= 0.0 ? tn : tf;
    if (!(t >= 0.0) || !(t < best_t)) continue;
    vec2 uv_m = chart_molecule_uv(g, s_over_S, mi.position.xyz);
    if (!membrane_keeps_copy(mt, uv_m, chart_position(chart, uv_m), molecules[mi.molecule_type].aabb_min.w)) {
      count_work(NANO_RC_OWNERSHIP_REJECTS);
      continue;
    }
    if (!membrane_copy_listed_shows(membrane_copy_listed(mt, membrane_copy_key(slot, m)), mi.flags)) {
      count_work(NANO_RC_LISTED_REJECTS);
      continue;
    }
    best_t = t;
    best.atom = a;
    best_type = mi.molecule_type;
    // The ellipsoid's normal: the tile-space sphere normal through the transpose of M1⁻¹.
    best_normal_c = normalize(transpose(chart_tile_frame_inverse_linear(chart, s_over_S)) * (ot + t * dt - centre));
    best.compartment_instance = inst;
    best.element = meshes[c.mesh].first_triangle + tl;
    best.kind = 0u;
    best.cell = ivec4(cell, 0, 0);
    best.instance = m;
    uvec2 number = copy_number_membrane(render_instances[inst].base.xy, tl, c.replication_width * c.replication_height,
                                        slot, rc.counts.x, m);
    best.copy_number_lo = number.x;
    best.copy_number_hi = number.y;
    found = true;
    rayQueryGenerateIntersectionEXT(q, t);
  }
  return found;
}

// The prism of triangle `tl` (local index in the mesh) of compartment `ci`: false when the ray misses
// it or clipping removes all it holds.
bool shell_walk_begin(uint ci, uint tl, vec3 o, vec3 d, out ShellWalk w) {
  Compartment c = compartments[ci];
  RenderCompartment rc = render_compartments[ci];
  Mesh mesh = meshes[c.mesh];
  uint t = mesh.first_triangle + tl;
  Triangle tri = triangles[t];
  uint f = mesh.first_vertex;
  vec3 p0 = positions[f + tri.v0].xyz;
  vec3 p1 = positions[f + tri.v1].xyz;
  vec3 p2 = positions[f + tri.v2].xyz;
  vec3 n0 = normals[f + tri.v0].xyz;
  vec3 n1 = normals[f + tri.v1].xyz;
  vec3 n2 = normals[f + tri.v2].xyz;
  TriangleShell sh = shells[t];
  ShellOffsets off;
  off.h_plus = sh.h_plus;
  off.h_minus = sh.h_minus;
  off.side = sh.side_offset;
  Prism pr = shell_prism_make(p0, p1, p2, n0, n1, n2, off);  // compiled out when neither test below is on
  count_work(NANO_RC_PRISM_TESTS);
  // The ray's part inside the prism, widened by a margin for rounding (jitter moves copies out).
  w.t_lo = 0.0;
  w.t_hi = best_t;
  if (kExactPrism) {
    PrismInterval iv;
    if (!prism_intersect(pr, o, d, 0.0, best_t, iv)) return false;
    if (!kJitter && !kTwoLevel) {
      float margin = 0.05 + 1e-5 * iv.t_exit;
      w.t_lo = max(iv.t_enter - margin, 0.0);
      w.t_hi = iv.t_exit + margin;
    }
  }
  count_work(NANO_RC_PRISMS_ENTERED);
  if (kClipping) {
    // µLAS-level trivial reject: every molecule the prism owns lies in the convex hull of its six
    // corners (bilinear walls included), so a hull wholly outside one half-space has nothing to show.
    vec3 lo = pr.v[0];
    vec3 hi = pr.v[0];
    for (int k = 1; k < 6; ++k) {
      lo = min(lo, pr.v[k]);
      hi = max(hi, pr.v[k]);
    }
    if (clip_removes_box(lo, hi)) return false;
  }
  w.mt.p0 = p0;
  w.mt.p1 = p1;
  w.mt.p2 = p2;
  w.mt.t0 = uvs[f + tri.v0];
  w.mt.t1 = uvs[f + tri.v1];
  w.mt.t2 = uvs[f + tri.v2];
  w.mt.seam_edges = sh.seam_edges;
  // A package without drops gets a zero record per triangle from the loader (levels/sections.cpp).
  TriangleDrops td = triangle_drops[t];
  w.mt.drop_first = td.first;
  w.mt.drop_count = td.count;
  w.chart = chart_make(p0, p1, p2, w.mt.t0, w.mt.t1, w.mt.t2, n0, n1, n2);
  uint cls = orders[rc.core_skip.y + tl];
  w.squares = cls & ~NANO_LIFT_UNSHEARED;
  w.lift = chart_smooth_lift_coefficients(w.chart, (cls & NANO_LIFT_UNSHEARED) != 0u ? 0.0 : c.scales.w);
  w.lift_directions = chart_lift_directions(w.chart, rc.membrane.y);
  float s = rc.membrane.x;
  vec2 uv_min = min(w.mt.t0, min(w.mt.t1, w.mt.t2));
  vec2 uv_max = max(w.mt.t0, max(w.mt.t1, w.mt.t2));
  w.origin = replication_origin(uv_min, s);
  w.extent = min(replication_extent(uv_min, uv_max, s), ivec2(c.replication_width, c.replication_height));
  bool rep = kReplicationLas && rc.span.w != NANO_NO_INDEX;
  w.mode = !rep ? kWalkAllSlots : !kLargeAreas || uint(w.extent.x * w.extent.y) <= NANO_DIRECT_SLOTS ? kWalkSlotBoxes : kWalkRepLas;
  // Every tile of the triangle shares M1's linear part: slot (i, j)'s box is the origin tile's moved
  // by (i·S, j·S, 0) in the origin tile's space.
  chart_tile_inverse_ray(w.chart, replication_tile_uv(w.origin, s), rc.membrane.y, o, d, w.ot, w.dt);
  return true;
}

// Replication slot `cell` (tile `tile` of the membrane recipe) of the prism walk w.
void membrane_element_query(RenderCompartment rc, ShellWalk w, uint tile, ivec2 cell, vec3 o, vec3 d, inout ElementQuery e) {
  float s_over_S = rc.membrane.y;
  e.entry = frame.levels.x + w.squares + tile;  // the mLAS of the triangle's distortion class
  e.first = squares[tile].first_instance;
  e.g = replication_tile_uv(cell, rc.membrane.x);
  chart_tile_inverse_ray(w.chart, e.g, s_over_S, o, d, e.ot, e.dt);
  // Its mLAS boxes stand on the tile's lift plane, not on the facet (levels/membrane.cpp, square_boxes).
  vec2 centre = vec2(rc.membrane.z);
  chart_lift_shear_ray(chart_smooth_lift_plane(w.chart, w.lift, w.lift_directions, e.g, s_over_S, centre), centre, e.ot, e.dt);
  e.q_lo = w.t_lo;
  e.q_hi = min(best_t, w.t_hi);
}

// The next slot of the prism walk w's area from `step` on, in order: every one (kWalkAllSlots) or each
// whose box the ray meets (kWalkSlotBoxes). False when none is left.
bool next_slot_in_order(RenderCompartment rc, ShellWalk w, inout uint step, inout ivec2 element) {
  while (step < uint(w.extent.x * w.extent.y)) {
    ivec2 sxy = ivec2(int(step % uint(w.extent.x)), int(step / uint(w.extent.x)));
    ++step;
    if (w.mode == kWalkSlotBoxes) {
      vec3 shift = vec3(float(sxy.x) * rc.slot_lo.w, float(sxy.y) * rc.slot_lo.w, 0.0);
      float tn;
      float tf;
      if (!aabb_intersect(rc.slot_lo.xyz + shift, rc.slot_hi.xyz + shift, w.ot, w.dt, w.t_lo, min(best_t, w.t_hi), tn, tf)) continue;
    }
    element = sxy;
    return true;
  }
  return false;
}

// The membrane copies of prism `prim` of instance `inst` (compartment `ci`) on the ray (o, od): the
// slots of its triangle's replication area the ray meets, each traced by trace_element. False when
// the triangle is in the flat level, the ray misses its prism or it found no nearer hit.
bool trace_prism(uint inst, uint ci, Compartment c, RenderCompartment rc, uint prim, bool use_flat, vec3 o, vec3 od) {
  uint tl = orders[rc.counts.w + prim];
  if (use_flat && triangle_flattened(render_instances[inst].base.w + tl)) return false;  // its copies are in the flat level
  ShellWalk w;
  if (!shell_walk_begin(ci, tl, o, od, w)) return false;
  bool found = false;
  rayQueryEXT area;  // kWalkRepLas: the replication area's tile boxes
  if (kRepLasWalk && w.mode == kWalkRepLas) {
    RenderLevel a = levels[rc.span.w];
    count_work(NANO_RC_REPLAS_QUERIES);
    rayQueryInitializeEXT(area, accelerationStructureEXT(a.address), kAabbOnly, 0xFF, w.ot, w.t_lo, w.dt, min(best_t, w.t_hi));
  }
  uint step = 0u;  // slots walked
  while (true) {
    // The next slot of the area.
    ivec2 element = ivec2(0);
    bool next = false;
    if (kRepLasWalk && w.mode == kWalkRepLas) {
      while (!next && rayQueryProceedEXT(area)) {
        uint p = uint(rayQueryGetIntersectionPrimitiveIndexEXT(area, false));
        RenderLevel a = levels[rc.span.w];
        if (p >= a.count) continue;
        uint slot = orders[a.order_first + p];
        ivec2 sxy = ivec2(int(slot % c.replication_width), int(slot / c.replication_width));
        if (sxy.x >= w.extent.x || sxy.y >= w.extent.y) continue;
        element = sxy;
        next = true;
      }
    } else {
      next = next_slot_in_order(rc, w, step, element);
    }
    if (!next) break;
    count_work(NANO_RC_SLOTS_TRIED);
    uint slot = uint(element.x) + c.replication_width * uint(element.y);
    if (!trace_element(inst, ci, c, rc, true, tl, w, slot, ivec3(replication_tile_index(w.origin, element), 0), o, od)) continue;
    found = true;
    if (kRepLasWalk && w.mode == kWalkRepLas && best_t >= w.t_lo) rayQueryGenerateIntersectionEXT(area, best_t);
  }
  return found;
}
