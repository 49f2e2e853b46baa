#version 460
// Smoke test of ray queries over procedural geometry: one invocation per ray, one TLAS whose
// instances hold BLASes of sphere AABBs. The shader tests each candidate AABB against its exact
// sphere and reports the nearest hit, so the CPU can check t against analytic geometry.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require
#include "shared/smoke_ray_query.h"

layout(local_size_x_id = 0) in;  // workgroup size is a specialization constant

layout(set = 0, binding = 0) uniform accelerationStructureEXT scene;
layout(set = 0, binding = 1, std430) readonly buffer Rays { SmokeRay rays[]; };
layout(set = 0, binding = 2, std430) readonly buffer Spheres { vec4 spheres[]; };  // object-space centre, radius
layout(set = 0, binding = 3, std430) writeonly buffer Hits { SmokeHit hits[]; };
layout(push_constant) uniform Push { uint ray_count; };

// Nearest root of |o + t d - c| = r within [t_min, t_max], after Ray Tracing Gems ch. 7: the
// discriminant comes from the perpendicular distance of the centre to the ray (no catastrophic
// cancellation for distant spheres), and the smaller root from the product of roots (no
// cancellation when the origin is near the surface). `d` need not be unit length.
bool nearest_sphere_hit(vec3 o, vec3 d, vec3 c, float r, float t_min, float t_max, out float t) {
  vec3 f = o - c;
  float a = dot(d, d);
  float t_closest = -dot(f, d) / a;
  float perpendicular = length(f + t_closest * d);
  float discriminant = (r - perpendicular) * (r + perpendicular);  // r^2 - l^2, factored
  if (discriminant < 0.0) return false;
  float h = sqrt(discriminant / a);
  float far_magnitude = t_closest + (t_closest >= 0.0 ? h : -h);  // root of larger magnitude
  float distance_to_centre = length(f);
  float product = (distance_to_centre - r) * (distance_to_centre + r) / a;  // t0 * t1
  float other = far_magnitude != 0.0 ? product / far_magnitude : 0.0;
  float t_near = min(far_magnitude, other);
  float t_far = max(far_magnitude, other);
  if (t_near >= t_min && t_near <= t_max) { t = t_near; return true; }
  if (t_far >= t_min && t_far <= t_max) { t = t_far; return true; }  // origin inside, or t_min past the entry
  return false;
}

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= ray_count) return;
  SmokeRay ray = rays[index];

  rayQueryEXT query;
  rayQueryInitializeEXT(query, scene, gl_RayFlagsNoneEXT, 0xFF, ray.origin_tmin.xyz, ray.origin_tmin.w,
                        ray.direction_tmax.xyz, ray.direction_tmax.w);
  // Generated hits must not lie beyond the committed one; track it here rather than read the
  // committed t, which is undefined until something is committed.
  float best_t = ray.direction_tmax.w;
  while (rayQueryProceedEXT(query)) {
    if (rayQueryGetIntersectionTypeEXT(query, false) != gl_RayQueryCandidateIntersectionAABBEXT) continue;
    // The object-space ray keeps the world-space parameterisation: t is the same in both.
    vec3 origin = rayQueryGetIntersectionObjectRayOriginEXT(query, false);
    vec3 direction = rayQueryGetIntersectionObjectRayDirectionEXT(query, false);
    vec4 sphere = spheres[rayQueryGetIntersectionPrimitiveIndexEXT(query, false)];
    float t;
    if (nearest_sphere_hit(origin, direction, sphere.xyz, sphere.w, rayQueryGetRayTMinEXT(query), best_t, t)) {
      best_t = t;
      rayQueryGenerateIntersectionEXT(query, t);
    }
  }

  SmokeHit hit = SmokeHit(-1.0, ~0u, ~0u, ~0u);
  if (rayQueryGetIntersectionTypeEXT(query, true) == gl_RayQueryCommittedIntersectionGeneratedEXT) {
    hit.t = rayQueryGetIntersectionTEXT(query, true);
    hit.instance_custom_index = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(query, true));
    hit.instance_id = uint(rayQueryGetIntersectionInstanceIdEXT(query, true));
    hit.primitive_id = uint(rayQueryGetIntersectionPrimitiveIndexEXT(query, true));
  }
  hits[index] = hit;
}
