// Clipping (kClipping), not a level: the frame's half-spaces (RenderFrame.clip, from
// runtime/render/effects.hpp) moved into the space of the instance being traced, and the tests every
// level asks of them — an atom by its centre, a copy by its bounding sphere, a prism, grid or box by
// its AABB.
// From render.comp: frame (clip, effects.x); writes clip_c.

// The frame's camera-relative half-spaces in the compartment space of the instance whose
// object → world transform is `to_world`: n·(A c + b) + d = (Aᵀn)·c + (n·b + d), renormalised so
// distances are compartment Å (instances may scale).
void load_clip_half_spaces(mat4x3 to_world) {
  mat3 a = mat3(to_world);
  for (uint k = 0u; k < frame.effects.x && k < NANO_MAX_CLIP_HALF_SPACES; ++k) {
    vec4 w = frame.clip[k];
    vec3 n = transpose(a) * w.xyz;
    float len = length(n);
    clip_c[k] = vec4(n / len, (dot(w.xyz, to_world[3]) + w.w) / len);
  }
}

bool clip_removes_point(vec3 p) {
  for (uint k = 0u; k < frame.effects.x && k < NANO_MAX_CLIP_HALF_SPACES; ++k)
    if (!clip_keeps_point(clip_c[k], p)) return true;
  return false;
}

bool clip_removes_whole_ball(vec3 c, float r) {
  for (uint k = 0u; k < frame.effects.x && k < NANO_MAX_CLIP_HALF_SPACES; ++k)
    if (clip_removes_ball(clip_c[k], c, r)) return true;
  return false;
}

// True iff one half-space removes all of the AABB [lo, hi] (its corner nearest the kept side is out).
bool clip_removes_box(vec3 lo, vec3 hi) {
  for (uint k = 0u; k < frame.effects.x && k < NANO_MAX_CLIP_HALF_SPACES; ++k) {
    vec3 n = clip_c[k].xyz;
    vec3 best_corner = mix(lo, hi, greaterThan(n, vec3(0.0)));
    if (!clip_keeps_point(clip_c[k], best_corner)) return true;
  }
  return false;
}
