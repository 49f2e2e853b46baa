#version 460
// Compiles every shared placement header as GLSL (Vulkan 1.2) and calls each function once, so the
// CTest "placement_glsl_compile" proves the headers are valid GLSL, not only valid C++.
#extension GL_GOOGLE_include_directive : require
#include "shared/placement_common.h"
#include "shared/quaternion.h"
#include "shared/ownership.h"
#include "shared/tile_mapper.h"
#include "shared/ray_sphere.h"
#include "shared/ray_prism.h"
#include "shared/grid_dda.h"
#include "shared/core_skip.h"

layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Io { vec4 data[]; } io;

void main() {
  uint i = gl_GlobalInvocationID.x;
  vec3 o = io.data[i].xyz;
  vec3 d = io.data[i + 1u].xyz;
  vec4 acc = vec4(0.0f);

  vec4 q = quat_mul(quat_from_axis_angle(d, 0.5f), quat_conjugate(quat_identity()));
  acc.xyz += quat_rotate(q, o) + quat_to_mat3(q) * d;

  bool own = own_triangle_owns(vec2(0.0f), vec2(1.0f, 0.0f), vec2(0.0f, 1.0f), o.xy);
  acc.w += own ? 1.0f : 0.0f;

  TriangleChart c = chart_make(o, o + vec3(1, 0, 0), o + vec3(0, 1, 0), vec2(0), vec2(1, 0), vec2(0, 1),
                               vec3(0, 0, 1), vec3(0, 0, 1), vec3(0, 0, 1));
  if (chart_valid(c)) acc.w += 1.0f;
  acc.xyz += chart_barycentric(c, o.xy) + chart_normal(c, o.xy) + vec3(chart_global_scale(2.0f, 1.0f));
  Affine3 m1 = chart_tile_frame(c, vec2(0.25f), 0.01f);
  Affine3 m1i = chart_tile_frame_inverse(c, vec2(0.25f), 0.01f);
  acc.xyz += affine_point(affine_compose(m1i, m1), o) + affine_vector(m1, d);
  vec3 ot; vec3 dt;
  chart_tile_inverse_ray(c, vec2(0.25f), 0.01f, o, d, ot, dt);
  vec2 uvm;
  Affine3 m2 = chart_membrane_molecule(c, vec2(0.25f), 0.01f, 0.75f, vec3(1, 2, 3), q, uvm);
  acc.xyz += chart_smooth_position(c, o.xy, 0.75f) + vec3(chart_smooth_bulge(c, 0.75f));
  molecule_inverse_ray(m2, o, d, ot, dt);
  Affine3 m3 = core_soluble_molecule(core_box_min(vec3(0), vec3(100), ivec3(1, 2, 3)), vec3(5), q);
  affine_inverse_ray(m3, o, d, ot, dt);
  acc.xyz += ot + dt + vec3(uvm, 0.0f);
  ivec2 ro = replication_origin(vec2(0.1f), 0.05f);
  ivec2 re = replication_extent(vec2(0.1f), vec2(0.3f), 0.05f) + replication_extent_bound(vec2(0.1f), vec2(0.3f), 0.05f);
  acc.xy += replication_tile_uv(replication_tile_index(ro, re), 0.05f);

  float tn; float tf;
  if (sphere_intersect(o, d, vec3(0), 1.5f, tn, tf)) acc.w += tn + tf;

  Prism pr;
  for (int k = 0; k < 6; ++k) pr.v[k] = io.data[i + uint(k) + 2u].xyz;
  PrismInterval pi;
  if (prism_intersect(pr, o, d, 0.0f, 1e30f, pi)) acc.w += pi.t_enter + pi.t_exit + float(pi.hit_count) + (pi.origin_inside ? 1.0f : 0.0f);

  if (aabb_intersect(vec3(0), vec3(1), o, d, 0.0f, 1e30f, tn, tf)) acc.w += tn;
  GridDda it;
  dda_init(it, vec3(0), vec3(10), ivec3(4, 5, 6), o, d, 0.0f, 1e30f);
  ivec3 cell; float ta; float tb;
  while (dda_next(it, cell, ta, tb)) acc += vec4(vec3(cell), tb - ta);
  dda_init(it, vec3(0), vec3(10), ivec3(4, 5, 6), o, d, 0.0f, 1e30f);
  while (dda_current(it, cell, ta)) {
    uint level = core_skip_level_in_word(floatBitsToUint(io.data[i].w), uint(cell.x));
    if (level != 0u) {
      ivec3 lo = core_skip_block_lo(cell, level);
      dda_skip_block(it, lo, core_skip_block_hi(lo, level, ivec3(4, 5, 6)));
    }
    acc.w += dda_advance(it);
  }

  io.data[i] = acc;
}
