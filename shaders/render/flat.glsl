// The flat level: the membrane copies of the triangles nearest the eye, each an instance of its
// type's nLAS in one TLAS (runtime/render/levels/flat.cpp) that trace_scene queries before the µLAS;
// trace_prism skips a flattened triangle's prism.
// From render.comp: flat_copies, flat_triangles, levels, orders, atoms, frame; the best hit (best_t,
// best, best_type, best_normal_c, best_to_world); count_work.

bool triangle_flattened(uint bit) {
  return (bit >> 5) < uint(flat_triangles.length()) && ((flat_triangles[bit >> 5] >> (bit & 31u)) & 1u) != 0u;
}

// A candidate of the flat level (a TLAS of copies, each an instance of its molecule type's nLAS BLAS,
// so every candidate is an atom box in molecule space: the ray the hardware transformed, as explicit
// instancing traces): copy `c`, primitive `p`, the molecule-space ray (om, dm) and the copy's
// transforms. True iff it is the nearest hit so far (ids recorded). Every index read from the level is
// checked against the buffer it names.
bool flat_atom_hit(uint c, uint p, vec3 om, vec3 dm, mat4x3 object_to_world, mat4x3 world_to_object) {
  count_work(NANO_RC_FLAT_CANDIDATES);
  if (c >= uint(flat_copies.length())) return false;
  FlatCopy fc = flat_copies[c];
  if (fc.molecule_type >= frame.levels.z) return false;
  RenderLevel level = levels[fc.molecule_type];
  if (p >= level.count) return false;
  uint a = orders[level.order_first + p];
  vec4 cr = atoms[a].centre_radius;
  float tn;
  float tf;
  count_work(NANO_RC_SPHERE_TESTS);
  if (!sphere_intersect(om, dm, cr.xyz, cr.w, tn, tf)) return false;
  float t = tn >= 0.0 ? tn : tf;
  if (!(t >= 0.0) || !(t < best_t)) return false;
  // An atom is clipped whole, by its centre (clip_c is in the level's space: see trace_scene).
  if (kClipping && clip_removes_point(object_to_world * vec4(cr.xyz, 1.0))) return false;
  best_t = t;
  best.compartment_instance = fc.compartment_instance;
  best.element = fc.element;
  best.kind = fc.kind;
  best.cell = fc.cell;
  best.instance = fc.instance;
  best.atom = a;
  best.copy_number_lo = fc.number_lo;
  best.copy_number_hi = fc.number_hi;
  best_type = fc.molecule_type;
  // World normal by the inverse transpose (an instance may scale); the hit's "compartment" is the world.
  best_normal_c = normalize(transpose(mat3(world_to_object)) * (om + t * dm - cr.xyz));
  best_to_world = mat4x3(1.0);
  return true;
}
