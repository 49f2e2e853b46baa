// The medium: the plasma between the cells, one periodic region of Wang cubes walked by a 3D-DDA
// after the µLAS, each copy kept only when clear of every compartment instance (a point query of the
// exclusion TLAS). Built by runtime/render/levels/medium.cpp (exclusion structure, reach, the eye's
// box); the cubes' mLASes are the core's (levels/core.cpp).
// From render.comp: medium, render_medium, medium_instances, exclusion_fields, exclusion_values,
// exclusion_tlas, cubes, instances, molecules, levels, orders; the best hit, eye_lo; count_work.

// Whether the medium copy centred at region-space c (medium_copy_centre) with radius r stands clear
// of every compartment instance: the instances whose exclusion box holds c (a point query of the
// exclusion structure), each by its field (shared/medium.h, as the CPU oracle decides).
bool medium_copy_kept(vec3 c, float r) {
  float clearance = medium[0].region_max.w;
  uint n = render_medium.numbers.z;
  bool kept = true;
  count_work(NANO_RC_MEDIUM_KEEP_QUERIES);
  rayQueryEXT e;
  rayQueryInitializeEXT(e, exclusion_tlas, kAabbOnly, 0xFF, c, 0.0, vec3(0.57735027), 1e-3);
  while (rayQueryProceedEXT(e)) {
    uint i = uint(rayQueryGetIntersectionPrimitiveIndexEXT(e, false));
    if (i >= n) continue;
    MediumInstance m = medium_instances[i];
    if (m.ids.x >= uint(exclusion_fields.length())) continue;
    ExclusionField f = exclusion_fields[m.ids.x];
    ivec3 cell;
    vec3 frac;
    if (!exclusion_cell(f, medium_to_compartment(m, c), cell, frac)) continue;
    float corners[8];
    for (int k = 0; k < 8; ++k) corners[k] = exclusion_values[exclusion_node(f, cell + ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1))];
    if (!medium_copy_clear(exclusion_trilinear(corners, frac), f, m.stretch.x, r, clearance)) {
      kept = false;
      rayQueryTerminateEXT(e);
    }
  }
  return kept;
}

// The medium copies of region box ijk on the ray (o, d) in eye-box space: the box's cube from the
// medium's periodic recipe, its mLAS, the copy's sphere, the keep rule, then its atoms.
bool trace_medium_box(ivec3 ijk, vec3 o, vec3 d) {
  Medium md = medium[0];
  float B = md.region_min.w;
  vec3 box_min = vec3(ijk - render_medium.eye_box.xyz) * B;
  float tn;
  float tf;
  if (!aabb_intersect(box_min + render_medium.reach_lo.xyz, box_min + render_medium.reach_hi.xyz, o, d, 0.0, best_t, tn, tf)) return false;
  if (kClipping && clip_removes_box(box_min + render_medium.reach_lo.xyz, box_min + render_medium.reach_hi.xyz)) return false;
  uint cube = recipe_cell(md.boxes.w, ijk);
  RenderLevel level = levels[frame.levels.y + cube];
  if (level.count == 0u) return false;
  uint first = cubes[cube].first_instance;
  uint box = uint(ijk.x) + md.boxes.x * (uint(ijk.y) + md.boxes.y * uint(ijk.z));
  bool found = false;
  count_work(NANO_RC_MLAS_QUERIES);
  rayQueryEXT q;
  rayQueryInitializeEXT(q, accelerationStructureEXT(level.address), kAabbOnly, 0xFF, o - box_min, 0.0, d, best_t);
  while (rayQueryProceedEXT(q)) {
    count_work(NANO_RC_MLAS_CANDIDATES);
    uint p = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false));
    if (p >= level.count) continue;
    uint m = orders[level.order_first + p];
    MoleculeInstance mi = instances[first + m];
    if (type_hidden(mi.molecule_type)) continue;
    float r = molecules[mi.molecule_type].aabb_min.w;
    // The ray must meet the copy's sphere before the keep rule's query is worth asking.
    if (!sphere_intersect(o, d, box_min + mi.position.xyz, r, tn, tf) || tf < 0.0 || tn > best_t) continue;
    if (!medium_copy_kept(medium_copy_centre(ijk, B, mi.position.xyz), r)) {
      count_work(NANO_RC_MEDIUM_REJECTS);
      continue;
    }
    Affine3 placement = core_soluble_molecule(box_min, mi.position.xyz, mi.rotation);
    uvec2 number = copy_number_core(render_medium.numbers.xy, uvec2(0u), box, md.tiles.z, m);
    if (kClipping && clip_removes_whole_ball(placement.translation, r)) continue;
    if (kJitter) placement = jittered(placement, number);
    // The oracle places medium copies exactly (region corner + box + position, in double): the
    // translation's float rounding goes back in as its low part.
    vec3 translation_hi;
    vec3 translation_lo;
    two_diff(box_min, -mi.position.xyz, translation_hi, translation_lo);
    if (!trace_molecule(mi.molecule_type, placement, translation_lo, o, d, 0.0)) continue;
    found = true;
    best.compartment_instance = NANO_MEDIUM_OWNER;
    best.element = box;
    best.kind = NANO_KIND_MEDIUM;
    best.cell = ivec4(ijk, 0);
    best.instance = m;
    best.copy_number_lo = number.x;
    best.copy_number_hi = number.y;
    rayQueryGenerateIntersectionEXT(q, best_t);
  }
  return found;
}

// The medium on the ray (origin camera-relative world, unit d) up to best_t: a 3D-DDA over the
// region's boxes widened by one (a copy reaches at most one box beyond its own), at each cell the
// boxes within one step not traced at the cell before, as the core walk does; in eye-box space.
void trace_medium(vec3 origin, vec3 d) {
  Medium md = medium[0];
  float B = md.region_min.w;
  ivec3 boxes = ivec3(md.boxes.xyz);
  ivec3 eye_box = render_medium.eye_box.xyz;
  vec3 o = render_medium.eye_hi.xyz + origin;
  eye_lo = render_medium.eye_lo.xyz;
  if (kClipping) load_clip_half_spaces(mat4x3(vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), vec3(0.0, 0.0, 1.0), -render_medium.eye_hi.xyz));
  GridDda it;
  dda_init(it, vec3(ivec3(-1) - eye_box) * B, vec3(B), boxes + ivec3(2), o, d, 0.0, best_t);
  ivec3 cell;
  float ta;
  ivec3 previous = ivec3(-1000000);
  bool found = false;
  while (dda_current(it, cell, ta)) {
    if (ta > best_t) break;
    count_work(NANO_RC_MEDIUM_STEPS);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          ivec3 ijk = cell - ivec3(1) + ivec3(dx, dy, dz);
          if (any(lessThan(ijk, ivec3(0))) || any(greaterThanEqual(ijk, boxes))) continue;
          ivec3 from_previous = abs(ijk - (previous - ivec3(1)));
          if (max(from_previous.x, max(from_previous.y, from_previous.z)) <= 1) continue;
          if (trace_medium_box(ijk, o, d)) found = true;
        }
    previous = cell;
    dda_advance(it);
  }
  if (found) best_to_world = mat4x3(vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), vec3(0.0, 0.0, 1.0), -render_medium.eye_hi.xyz);
}
