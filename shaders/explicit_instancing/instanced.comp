#version 460
// Explicit instancing, the conventional design the virtual renderer (shaders/render/render.comp) is
// measured against (runtime/explicit_instancing/): one TLAS with one instance per molecule copy, each
// referencing its molecule type's BLAS of atom boxes. One ray query per pixel; every candidate box
// is an atom, tested as a sphere in the copy's object (molecule) space with the ray the hardware
// transformed. Hit rule (as render.comp and the oracle): the smallest root t ≥ 0; t along an affine
// object-space ray equals t along the unit world ray, so depths compare directly.
//
// Every index read from a buffer is checked against the buffer's length: a record that names
// something outside it is skipped, never read.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "shared/camera.h"
#include "shared/instanced_records.h"
#include "shared/ray_sphere.h"
#include "shared/ray_counters.h"

layout(local_size_x = NANO_WORKGROUP_SIZE, local_size_y = NANO_WORKGROUP_SIZE) in;

// Work counters per pixel, as render.comp's (shared/ray_counters.h): the TLAS is the top level.
layout(constant_id = NANO_SPEC_INSTANCED_COUNTERS) const bool kCounters = false;

// Records: shaders/shared/instanced_records.h; bindings: shaders/shared/bindings.h.
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_IB_TLAS) uniform accelerationStructureEXT tlas;
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_IB_COPIES, std430) readonly buffer Copies { InstancedCopy copies[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_IB_TYPES, std430) readonly buffer Types { InstancedType types[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_IB_ATOMS, std430) readonly buffer Atoms { vec4 atoms[]; };   // section atoms: centre, radius
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_IB_ORDERS, std430) readonly buffer Orders { uint orders[]; }; // BLAS primitive → atom index
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_IB_FRAME, std430) readonly buffer Frame { InstancedFrameRecord frame; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_IB_HITS, std430) writeonly buffer Hits { PixelHit hits[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_IB_COLOURS, std430) writeonly buffer Colours { uint colours[]; };  // RGBA8, sRGB
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_IB_COUNTERS, std430) writeonly buffer Counters { uint counters[]; };

vec3 srgb_from_linear(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

void main() {
  Camera cam = frame.camera;
  uvec2 px = gl_GlobalInvocationID.xy;
  if (px.x >= cam.size.x || px.y >= cam.size.y) return;
  uint index = px.y * cam.size.x + px.x;
  if (index >= uint(hits.length()) || index >= uint(colours.length())) return;
  vec3 d = camera_ray_direction(cam, px.x, px.y);

  PixelHit best;
  best.depth = placement_inf();
  best.compartment_instance = kNoHit;  // the copy's identity beyond its number is not kept here
  best.element = kNoHit;
  best.kind = kNoHit;
  best.cell = ivec4(-1);
  best.instance = kNoHit;
  best.atom = kNoHit;
  best.copy_number_lo = kNoHit;
  best.copy_number_hi = kNoHit;
  float best_t = placement_inf();
  vec3 best_normal_o = vec3(0.0);  // object-space outward normal (unnormalised) of the best atom
  mat3 best_world_to_object = mat3(1.0);
  uint best_type = 0u;

  uint candidates = 0u;
  uint sphere_tests = 0u;
  rayQueryEXT q;
  rayQueryInitializeEXT(q, tlas, gl_RayFlagsNoneEXT, 0xFF, frame.origin.xyz, 0.0, d, placement_inf());
  while (rayQueryProceedEXT(q)) {
    if (rayQueryGetIntersectionTypeEXT(q, false) != gl_RayQueryCandidateIntersectionAABBEXT) continue;
    if (kCounters) ++candidates;
    uint c = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(q, false));
    if (c >= uint(copies.length())) continue;
    InstancedCopy copy = copies[c];
    if (copy.molecule_type >= uint(types.length())) continue;
    uvec4 range = types[copy.molecule_type].range;
    uint p = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false));
    if (p >= range.y || range.x + p >= uint(orders.length())) continue;
    uint a = orders[range.x + p];
    if (a >= uint(atoms.length())) continue;
    vec4 cr = atoms[a];
    vec3 om = rayQueryGetIntersectionObjectRayOriginEXT(q, false);
    vec3 dm = rayQueryGetIntersectionObjectRayDirectionEXT(q, false);
    float tn;
    float tf;
    if (kCounters) ++sphere_tests;
    if (!sphere_intersect(om, dm, cr.xyz, cr.w, tn, tf)) continue;
    float t = tn >= 0.0 ? tn : tf;  // the eye inside an atom sees its far side
    if (!(t >= 0.0) || !(t < best_t)) continue;
    best_t = t;
    best.atom = a;
    best.copy_number_lo = copy.number_lo;
    best.copy_number_hi = copy.number_hi;
    best_type = copy.molecule_type;
    best_normal_o = om + t * dm - cr.xyz;
    best_world_to_object = mat3(rayQueryGetIntersectionWorldToObjectEXT(q, false));
    rayQueryGenerateIntersectionEXT(q, t);  // later candidates beyond t are culled by the traversal
  }

  vec3 colour = vec3(1.0);  // background
  if (best.atom != kNoHit) {
    best.depth = best_t;
    // Normals go through the inverse transpose (a non-rigid instance makes the sphere an ellipsoid).
    vec3 n = normalize(transpose(best_world_to_object) * best_normal_o);
    // The same simple shading as render.comp without effects or depth cue.
    float facing = abs(dot(n, d));
    float lambert = abs(dot(n, frame.light.xyz));
    colour = types[best_type].colour.rgb * ((0.25 + 0.2 * facing) + 0.55 * lambert);
  }
  hits[index] = best;
  uvec3 b = uvec3(round(srgb_from_linear(colour) * 255.0));
  colours[index] = b.r | (b.g << 8) | (b.b << 16) | (255u << 24);
  if (kCounters && (index + 1u) * NANO_RAY_COUNTER_COUNT <= uint(counters.length())) {
    for (uint k = 0u; k < NANO_RAY_COUNTER_COUNT; ++k) counters[index * NANO_RAY_COUNTER_COUNT + k] = 0u;
    counters[index * NANO_RAY_COUNTER_COUNT + NANO_RC_ULAS_QUERIES] = 1u;
    counters[index * NANO_RAY_COUNTER_COUNT + NANO_RC_ULAS_CANDIDATES] = candidates;
    counters[index * NANO_RAY_COUNTER_COUNT + NANO_RC_SPHERE_TESTS] = sphere_tests;
  }
}
