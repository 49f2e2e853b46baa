// The nLAS level and the bead levels (--lod): a copy's atoms, or its beads, on the ray by exact
// ray–sphere; every other level ends here. Built by runtime/render/levels/atoms.cpp (per molecule type
// a level over its atoms' boxes) and levels/beads.cpp (over its beads). Also what a copy's caller
// asks before it: jittered (kJitter) and type_hidden (kHiddenTypes).
// From render.comp: molecules, atoms, beads, levels, orders, frame (lod, effects.w,
// effect_parameters), eye_lo; the best hit (best_t, best, best_type, best_normal_c); count_work.

// The jittered placement of copy `number` (kJitter only).
Affine3 jittered(Affine3 m, uvec2 number) {
  vec4 p = frame.effect_parameters;
  return jitter_placement(m, jitter_rotation(number, p.y, p.z, p.w));
}

// A hidden type (kHiddenTypes): GpuScene::set_visibility emptied its level.
bool type_hidden(uint type) { return kHiddenTypes && levels[type].count == 0u; }

// The exact difference a − b of two floats as an unevaluated pair hi + lo (Knuth's TwoSum; `precise`
// keeps the compiler from reassociating it away or fusing it).
void two_diff(vec3 a, vec3 b, out vec3 hi, out vec3 lo) {
  precise vec3 s = a - b;
  precise vec3 bb = s - a;
  precise vec3 err = (a - (s - bb)) - (b + bb);
  hi = s;
  lo = err;
}

// Nearest atom of molecule type `type` placed by `m` (compartment space; its translation exactly
// m.translation + translation_lo) on the ray (o, d) within [t_lo, best_t] (t_lo: where the copy can
// begin along the ray, 0 when unknown); o is the compartment-space eye (high part, eye_lo the low).
// Updates best_t, best.atom and best_normal_c; true iff it found a nearer atom.
// The ray enters molecule space rebased to where it can first meet the copy (t0): the eye − copy
// vector kept exact as a float pair and t0·d added with its rounding error, so the molecule-space
// origin is as precise near a copy 4·10^5 Å away as near the eye (a float origin that far is off by
// 0.03 Å: another atom than explicit instancing's on ~1 % of a far view's pixels).
bool trace_molecule(uint type, Affine3 m, vec3 translation_lo, vec3 o, vec3 d, float t_lo) {
  vec3 s_hi;
  vec3 s_lo;
  two_diff(o, m.translation, s_hi, s_lo);
  s_lo += eye_lo - translation_lo;
  float dd = dot(d, d);
  float t0 = max(0.0, -dot(s_hi, d) / dd - molecules[type].aabb_min.w / sqrt(dd));
  precise vec3 p_hi = t0 * d;
  precise vec3 p_lo = fma(vec3(t0), d, -p_hi);
  precise vec3 rebased = (s_hi + p_hi) + (s_lo + p_lo);
  mat3 rt = transpose(m.linear);
  vec3 om = rt * rebased;
  vec3 dm = rt * d;
  // Beads when an atom of the copy, at the copy's distance, spans fewer than frame.lod.y pixels.
  bool coarse = kLod && frame.lod.z < frame.lod.y * frame.lod.x * length(m.translation - o);
  RenderLevel level = levels[coarse ? frame.effects.w + type : type];
  if (level.count == 0u) return false;
  bool found = false;
  float near_lo = max(t_lo - t0, 0.0);  // no hit lies before t0: it is where the copy's sphere begins
  float near_best = best_t - t0;          // best_t in the rebased ray's parameter, kept there
  count_work(NANO_RC_NLAS_QUERIES);
  rayQueryEXT q;
  rayQueryInitializeEXT(q, accelerationStructureEXT(level.address), kAabbOnly, 0xFF, om, near_lo, dm, near_best);
  while (rayQueryProceedEXT(q)) {
    count_work(NANO_RC_NLAS_CANDIDATES);
    uint p = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false));
    if (p >= level.count) continue;
    uint a = orders[level.order_first + p];
    vec4 cr = coarse ? beads[a].centre_radius : atoms[a].centre_radius;
    float tn;
    float tf;
    count_work(NANO_RC_SPHERE_TESTS);
    if (!sphere_intersect(om, dm, cr.xyz, cr.w, tn, tf)) continue;
    float t = tn >= -t0 ? tn : tf;  // the eye inside the atom: its far side
    if (!(t >= -t0) || !(t < near_best)) continue;
    // An atom is clipped whole, by its centre: never cut in half.
    if (kClipping && clip_removes_point(m.linear * cr.xyz + m.translation)) continue;
    near_best = t;
    best_t = t0 + t;
    best.atom = coarse ? beads[a].atom : a;
    best_type = type;
    best_normal_c = m.linear * normalize(om + t * dm - cr.xyz);
    found = true;
    if (t >= near_lo) rayQueryGenerateIntersectionEXT(q, t);  // a hit must lie in the query's range
  }
  return found;
}
