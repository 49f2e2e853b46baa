// Buffers of shaders/smoke_ray_query.comp, shared with the C++ smoke test.
#ifndef NANO_SMOKE_RAY_QUERY_H
#define NANO_SMOKE_RAY_QUERY_H
#include "shared/glsl_cpp.h"

NANO_BEGIN

struct SmokeRay {
  vec4 origin_tmin;     // world-space origin, t_min
  vec4 direction_tmax;  // world-space direction (not normalised), t_max
};

struct SmokeHit {
  float t;                     // committed t, or -1 on a miss
  uint instance_custom_index;  // ~0u on a miss
  uint instance_id;
  uint primitive_id;
};

// The workgroup size is specialization constant 0; the push-constant block holds the ray count.
NANO_CONST uint kSmokeWorkgroupSizeConstantId = 0u;

NANO_END

#ifdef __cplusplus
static_assert(sizeof(nano::gpu::SmokeRay) == 32);
static_assert(sizeof(nano::gpu::SmokeHit) == 16);
#endif
#endif
