// The records of explicit instancing (shaders/explicit_instancing/instanced.comp, runtime/explicit_instancing/), std430,
// declared once for GLSL and C++.
#ifndef NANO_INSTANCED_RECORDS_H
#define NANO_INSTANCED_RECORDS_H

#include "glsl_cpp.h"
#include "camera.h"

NANO_BEGIN

// Per TLAS instance (its custom index names it): the copy number's low and high words
// (oracle::Copy::number), its molecule type, and a reserved word.
struct InstancedCopy {
  uint number_lo;
  uint number_hi;
  uint molecule_type;
  uint reserved;
};

// Per molecule type: range.x the first entry in the orders buffer, range.y the primitives of the
// type's BLAS; colour: linear RGB.
struct InstancedType {
  uvec4 range;
  vec4 colour;
};

// The Frame block.
struct InstancedFrameRecord {
  Camera camera;
  vec4 origin;  // xyz: the eye in the TLAS's space (eye − anchor, rounded once from double)
  vec4 light;   // xyz: unit direction towards the light (world)
};

NANO_END

#ifdef __cplusplus
static_assert(sizeof(nano::gpu::InstancedCopy) == 16 && sizeof(nano::gpu::InstancedType) == 32 &&
              sizeof(nano::gpu::InstancedFrameRecord) == 112, "std430 sizes (tests/format/check_glsl_layout.cmake)");
#endif

#endif
