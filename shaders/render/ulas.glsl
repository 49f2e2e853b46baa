// The µLAS: one ray through the whole scene (trace_scene): the flat level's TLAS first, then the TLAS
// over compartment instances, whose candidates are membrane prisms (trace_prism) and core grids
// (trace_core_grid), then the medium. Built by runtime/render/levels/ulas.cpp (per compartment a BLAS
// of prisms and the grid's box, the instance TLAS for every eye, RenderInstance records).
// From render.comp: ulas, flat_tlas, render_instances, render_compartments, compartments, frame;
// writes the best hit and eye_lo; count_work; kFlat, kEyeFromHost, kMedium, kClipping.

// Forgets the best hit: nothing met yet up to t_max.
void reset_best(float t_max) {
  best_t = t_max;
  best.depth = placement_inf();
  best.compartment_instance = kNoHit;
  best.element = kNoHit;
  best.kind = kNoHit;
  best.cell = ivec4(-1);
  best.instance = kNoHit;
  best.atom = kNoHit;
  best.copy_number_lo = kNoHit;
  best.copy_number_hi = kNoHit;
  best_normal_c = vec3(0.0);
  best_type = 0u;
}

// Traces one ray through the whole scene: origin camera-relative world, unit direction d, hits in
// [0, t_max]. kEyeFromHost: the ray enters each instance's compartment space through the host's
// double computation (RenderInstance), not the driver's float WorldToObject: the eye as a two-float
// sum, a secondary ray's (AO, shadows) origin as the eye plus L⁻¹·origin. Leaves the hit in best*.
bool trace_scene(vec3 origin, vec3 d, float t_max, bool primary) {
  reset_best(t_max);
  bool use_flat = kFlat && frame.flat_eye.w != 0.0;
  // Two passes of one query: the flat level first (its hit bounds every µLAS candidate), then the
  // µLAS — one traversal in the compiled code, not two.
  rayQueryEXT q;
  for (bool flat_pass = use_flat;; flat_pass = false) {
  if (flat_pass) {
    // The level's space is camera-relative world moved by flat_eye: x_camera = x_level − flat_eye.
    if (kClipping) load_clip_half_spaces(mat4x3(vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), vec3(0.0, 0.0, 1.0), -frame.flat_eye.xyz));
    count_work(NANO_RC_FLAT_QUERIES);
    rayQueryInitializeEXT(q, flat_tlas, kAabbOnly, 0xFF, origin + frame.flat_eye.xyz, 0.0, d, best_t);
  } else {
    count_work(NANO_RC_ULAS_QUERIES);
    rayQueryInitializeEXT(q, ulas, kAabbOnly, 0xFF, origin, 0.0, d, best_t);
  }
  while (rayQueryProceedEXT(q)) {
    if (rayQueryGetIntersectionTypeEXT(q, false) != gl_RayQueryCandidateIntersectionAABBEXT) continue;
    if (flat_pass) {
      if (flat_atom_hit(uint(rayQueryGetIntersectionInstanceCustomIndexEXT(q, false)),
                        uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false)),
                        rayQueryGetIntersectionObjectRayOriginEXT(q, false),
                        rayQueryGetIntersectionObjectRayDirectionEXT(q, false),
                        rayQueryGetIntersectionObjectToWorldEXT(q, false),
                        rayQueryGetIntersectionWorldToObjectEXT(q, false)))
        rayQueryGenerateIntersectionEXT(q, best_t);
      continue;
    }
    count_work(NANO_RC_ULAS_CANDIDATES);
    uint inst = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(q, false));
    uint prim = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false));
    vec3 o;
    vec3 od;
    if (kEyeFromHost) {
      RenderInstance ri = render_instances[inst];
      mat3 from_world = transpose(mat3(ri.from_world[0].xyz, ri.from_world[1].xyz, ri.from_world[2].xyz));
      od = from_world * d;
      o = primary ? ri.eye_hi.xyz : ri.eye_hi.xyz + from_world * origin;
      eye_lo = ri.eye_lo.xyz;
    } else {
      o = rayQueryGetIntersectionObjectRayOriginEXT(q, false);
      od = rayQueryGetIntersectionObjectRayDirectionEXT(q, false);
      eye_lo = vec3(0.0);
    }
    if (kClipping) load_clip_half_spaces(rayQueryGetIntersectionObjectToWorldEXT(q, false));
    uint ci = render_instances[inst].base.z;
    RenderCompartment rc = render_compartments[ci];
    Compartment c = compartments[ci];
    bool membrane = prim < rc.counts.z;
    bool found;
    if (membrane)
      found = trace_prism(inst, ci, c, rc, prim, use_flat, o, od);
    else
      found = trace_core_grid(inst, ci, c, rc, o, od);
    if (found) {
      best_to_world = rayQueryGetIntersectionObjectToWorldEXT(q, false);
      rayQueryGenerateIntersectionEXT(q, best_t);
    }
  }
  if (!flat_pass) break;
  }
  if (kMedium) trace_medium(origin, d);
  return best.atom != kNoHit;
}
