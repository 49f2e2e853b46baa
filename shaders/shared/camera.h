// The pinhole camera and the per-pixel result every renderer writes (GLSL 460 and C++20/GLM, see
// glsl_cpp.h). The GPU renderer and the CPU oracle generate their rays with camera_ray() on the
// same floats, so a pixel names the same ray on both sides and only the traversal can differ.
#ifndef NANO_CAMERA_H
#define NANO_CAMERA_H
#include "shared/placement_common.h"

NANO_BEGIN

// Vertical field of view; right = normalize(forward × up), up' = right × forward; pixel centres at
// (x + ½, y + ½); pixel row 0 is the TOP row of the image. Positions in world Å.
struct Camera {
  vec4 position;      // xyz: eye; w: vertical field of view in degrees
  vec4 forward;       // xyz: unit viewing direction; w: tan(fov / 2)
  vec4 right;         // xyz: unit right vector; w: aspect = width / height
  vec4 up;            // xyz: unit up vector (right × forward); w: reserved (0)
  uvec4 size;         // x: width, y: height (pixels); zw: reserved (0)
};

// The orthonormal camera from eye, target and up hint. `at` must differ from `eye` and `up_hint`
// must not be parallel to at − eye (the caller checks; see camera_valid).
NANO_FN Camera camera_look_at(NANO_IN(vec3) eye, NANO_IN(vec3) at, NANO_IN(vec3) up_hint, float fov_degrees,
                              uint width, uint height) {
  Camera c;
  vec3 f = normalize(at - eye);
  vec3 r = normalize(cross(f, up_hint));
  vec3 u = cross(r, f);
  c.position = vec4(eye, fov_degrees);
  c.forward = vec4(f, tan(radians(fov_degrees) * 0.5f));
  c.right = vec4(r, float(width) / float(height));
  c.up = vec4(u, 0.0f);
  c.size = uvec4(width, height, 0u, 0u);
  return c;
}

// Unit world direction of the ray through the centre of pixel (x, y), row 0 at the top.
NANO_FN vec3 camera_ray_direction(NANO_IN(Camera) c, uint x, uint y) {
  float ndc_x = (2.0f * (float(x) + 0.5f) / float(c.size.x) - 1.0f) * c.forward.w * c.right.w;
  float ndc_y = (1.0f - 2.0f * (float(y) + 0.5f) / float(c.size.y)) * c.forward.w;
  return normalize(vec3(c.forward) + ndc_x * vec3(c.right) + ndc_y * vec3(c.up));
}

// What a renderer records for one pixel. depth = t along the unit world ray in Å, +inf for the
// background. Ids name the hit as docs/placement.md does; all kNoHit when nothing was hit.
NANO_CONST uint kNoHit = 0xFFFFFFFFu;
struct PixelHit {
  float depth;                 // Å along the unit ray; +inf: background
  uint compartment_instance;   // index into section compartment_instances
  uint element;                // as oracle::CopyId: membrane: index into section triangles; core: box linear index
  uint kind;                   // 0 membrane, 1 core
  ivec4 cell;                  // membrane: tile cell (a, b, 0, 0); core: box (i, j, k, 0)
  uint instance;               // molecule index within its Wang square or cube
  uint atom;                   // index into section atoms (as oracle::AtomSample::atom)
  uint copy_number_lo;         // ExplicitScene copy number (64 bits), low and high words
  uint copy_number_hi;
};

NANO_END
#endif
