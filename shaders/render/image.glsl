// Colour and the image pass, not a level: a colour word packed as sRGB (main's), and the effects
// that read the finished hits of a pixel's neighbours (outlines, fog) once every pixel is traced; the
// effect records are the frame's (runtime/render/effects.hpp).
// From render.comp: frame, finished_hits, molecules, colours; kOutlines, kFog.

vec3 srgb_from_linear(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

// A colour buffer word: RGBA8 as the image shows it (sRGB), R in the low byte, alpha 255.
uint rgba8_from_bytes(vec3 bytes) {
  uvec3 b = uvec3(round(bytes));
  return b.r | (b.g << 8) | (b.b << 16) | (255u << 24);
}
vec3 bytes_from_rgba8(uint rgba) { return vec3(uvec3(rgba, rgba >> 8, rgba >> 16) & uvec3(255u)); }

// The image pass (frame.pass.x = 1, after every pixel is traced): effects that read the finished
// hits of a pixel's neighbours (EffectDeclaration::image_pass in common/effect_table.hpp).

// Outlines (Goodsell's illustrations; Mol*'s illustrative style), legible at every distance: a pixel
// darkens towards the outline colour where a pixel within `width` (Chebyshev distance) is nearer and
// shows another molecule copy — the silhouette, drawn just outside the nearer copy — or the same copy
// nearer by more than the crease depth, where a copy folds over itself. The background is a copy of
// its own at infinite depth. Thresholds are measured on screen, at the nearer pixel's footprint:
// - a copy's contours ramp in as its bounding radius grows from fade/2 to fade pixels (fade 0: always
//   full), so a membrane seen whole is not a mesh of lines;
// - against the background the contour is always full: the silhouette of a cell seen whole;
// - where copies meet at a depth step of 8 to 32 pixel footprints (NANO_OUTLINE_STEP_PIXELS), the
//   contour ramps in whatever their size, once the nearer copy spans a few pixels (its radius from 1
//   to 3 pixels): the silhouettes of what is large on screen (a spike standing off the membrane, the
//   limb of a virion over its far side) stay; sub-pixel bumps and sub-pixel copies draw nothing (so
//   surfaces of sub-pixel copies crossing each other get no contour: docs/effects.md);
// - a crease ramps in from c to 2c, c the larger of the crease depth and 2 pixel footprints
//   (NANO_CREASE_PIXELS), scaled by the copy's own fade: from afar a spike keeps its big folds only.
// The strength in [0, 1] mixes the pixel's colour towards the outline colour: a grey ramp, not a switch.
const float NANO_OUTLINE_STEP_PIXELS = 8.0;
const float NANO_CREASE_PIXELS = 2.0;

float smooth_ramp(float lo, float hi, float x) {
  float u = clamp((x - lo) / (hi - lo), 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

// The bounding radius about the origin of the molecule type of `atom` (copies turn about it).
float reach_of_atom(uint atom) {
  for (uint m = 0u; m < frame.levels.z; ++m)
    if (atom >= molecules[m].first_atom && atom - molecules[m].first_atom < molecules[m].atom_count) return molecules[m].aabb_min.w;
  return 0.0;
}

float outline_strength(uvec2 px, uint index) {
  int width = int(frame.effect_record.outline_width_pixels);
  float crease = frame.effect_record.outline_crease_depth;
  float fade = frame.effect_record.outline_fade_pixels;
  PixelHit here = finished_hits[index];
  bool here_hit = here.atom != kNoHit;
  float here_depth = here_hit ? here.depth : placement_inf();
  ivec2 size = ivec2(frame.camera.size.xy);
  float strength = 0.0;
  for (int dy = -width; dy <= width; ++dy)
    for (int dx = -width; dx <= width; ++dx) {
      ivec2 q = ivec2(px) + ivec2(dx, dy);
      if (q.x < 0 || q.y < 0 || q.x >= size.x || q.y >= size.y) continue;
      PixelHit there = finished_hits[uint(q.y) * uint(size.x) + uint(q.x)];
      if (there.atom == kNoHit || !(there.depth < here_depth)) continue;  // only a nearer neighbour draws here
      float pixel = max(there.depth * frame.lod.x, 1e-30);  // Å one pixel spans at the nearer hit
      float reach = reach_of_atom(there.atom);
      float shown = fade > 0.0 ? smooth_ramp(0.5 * fade, fade, reach / pixel) : 1.0;
      float gap = here_depth - there.depth;
      bool same = here_hit && there.copy_number_lo == here.copy_number_lo && there.copy_number_hi == here.copy_number_hi;
      float fold = max(crease, NANO_CREASE_PIXELS * pixel);
      float step = here_hit ? smooth_ramp(NANO_OUTLINE_STEP_PIXELS, 4.0 * NANO_OUTLINE_STEP_PIXELS, gap / pixel) * smooth_ramp(1.0, 3.0, reach / pixel)
                            : 1.0;
      float edge = same ? shown * smooth_ramp(fold, 2.0 * fold, gap) : max(shown, step);
      strength = max(strength, edge);
    }
  return strength;
}

uint mix_rgba8(uint a, uint b, float s) { return rgba8_from_bytes(mix(bytes_from_rgba8(a), bytes_from_rgba8(b), s)); }

// Fog (depth cueing): a hit pixel's colour fades towards the background (white, in linear light) as its
// view depth (its distance along the camera's forward axis: a wall facing the camera is one depth)
// passes through the frame's depth range, smoothly from start to start + span of that range, at most
// by `strength`. The range is the least and greatest view depth hit among the pixels of an 8 × 8 grid
// (pixel (⌊(2i + 1)·W / 16⌋, ⌊(2j + 1)·H / 16⌋)), its extent at least a tenth of the nearest
// depth, so the cue spans what the frame shows at any
// scale: the rim and the dimple of a red cell seen whole, the cells behind a cell in blood, the
// lipids behind a protein. No grid pixel hit: no fog.
float view_depth(uvec2 px, float t) { return t * dot(camera_ray_direction(frame.camera, px.x, px.y), frame.camera.forward.xyz); }

vec2 frame_depth_range() {
  uvec2 size = frame.camera.size.xy;
  vec2 range = vec2(placement_inf(), -placement_inf());
  for (uint j = 0u; j < 8u; ++j)
    for (uint i = 0u; i < 8u; ++i) {
      uvec2 q = uvec2((2u * i + 1u) * size.x / 16u, (2u * j + 1u) * size.y / 16u);
      PixelHit h = finished_hits[q.y * size.x + q.x];
      if (h.atom != kNoHit) range = vec2(min(range.x, view_depth(q, h.depth)), max(range.y, view_depth(q, h.depth)));
    }
  return range;
}

// The range spans at least a tenth of its nearest depth (NANO_FOG_LEAST_EXTENT): a patch of membrane
// seen face-on, a few Å deep at 6,000 Å, is not stretched into a full ramp.
const float NANO_FOG_LEAST_EXTENT = 0.1;

float fog_amount(float t, vec2 range) {
  if (!(range.x <= range.y)) return 0.0;
  float extent = max(range.y - range.x, NANO_FOG_LEAST_EXTENT * range.x);
  float start = range.x + frame.effect_record.fog_range.x * extent;
  float end = start + frame.effect_record.fog_range.y * extent;
  float ramp = end > start ? smooth_ramp(start, end, t) : (t > start ? 1.0 : 0.0);
  return frame.effect_record.fog_strength * ramp;
}

vec3 linear_from_srgb(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

uint fogged_rgba8(uint rgba, float amount) {
  vec3 c = linear_from_srgb(bytes_from_rgba8(rgba) / 255.0);
  return rgba8_from_bytes(srgb_from_linear(mix(c, vec3(1.0), amount)) * 255.0);
}

// Any image-pass effect compiled in: without one, the pass test below is not in the code at all.
const bool kImagePass = kOutlines || kFog;

// Fog first, on the hit pixels by their own depth; then the contours over it, unfogged.
void image_pass(uvec2 px, uint index) {
  if (kFog) {
    PixelHit here = finished_hits[index];
    if (here.atom != kNoHit) {
      float amount = fog_amount(view_depth(px, here.depth), frame_depth_range());
      if (amount > 0.0) colours[index] = fogged_rgba8(colours[index], amount);
    }
  }
  if (kOutlines) {
    float s = outline_strength(px, index);
    if (s > 0.0) colours[index] = mix_rgba8(colours[index], frame.effect_record.outline_colour, s);
  }
}
