// Records the renderer derives from a package at load time (runtime/render/levels/) and its
// shader (shaders/render/render.comp) reads next to the package's own sections. std430 = C++ layout
// by the same rules as package_records.h (vec4/uvec4 members at multiples of 16 bytes).
#ifndef NANO_RENDER_SCENE_H
#define NANO_RENDER_SCENE_H
#include "shared/camera.h"
#include "shared/package_records.h"

NANO_BEGIN

// Per compartment (parallel to section "compartments").
struct RenderCompartment {
  vec4 membrane;   // x: tile UV size s; y: s / S; z: S/2, the tile point (z, z) of its lift plane; w: reserved
  vec4 reach_lo;   // xyz: cube-space minimum of every cube molecule's bounding sphere (≥ −box edge); w: reserved
  vec4 reach_hi;   // xyz: cube-space maximum (≤ 2·box edge); w: reserved
  uvec4 counts;    // x: I₂ (largest square instance count); y: I₃ (cubes); z: prism primitives in the
                   // compartment's µLAS BLAS (the core-grid box, if any, is primitive z); w: first entry
                   // of its primitive → triangle map in `orders`
  uvec4 span;      // xy: membrane copy-number span of one instance (lo, hi); z: 1 = has a core grid;
                   // w: repLAS entry in `levels` (NANO_NO_INDEX: none)
  vec4 slot_lo;    // xyz: tile-space minimum of every mLAS box of the compartment's squares (the
                   // repLAS box of slot (0, 0); slot (i, j) is moved by (i·S, j·S, 0)); w: S
  vec4 slot_hi;    // xyz: tile-space maximum; w: reserved
  uvec4 core_skip; // x: the core grid's first cell in section "core_skip" (shared/core_skip.h); y: first
                   // entry in `orders` of the mesh's triangles' distortion classes (per triangle, its
                   // class's first square level minus frame.levels.x, | NANO_LIFT_UNSHEARED); zw: reserved
};

// Set in a triangle's distortion-class word: its slots' rays are not sheared onto the tile's lift
// plane (chart_lift_shear_ray), whose extrapolation over a tile would widen its boxes more than the
// whole lift does (a sliver, or a facet smaller than a tile).
NANO_CONST uint NANO_LIFT_UNSHEARED = 0x80000000u;

// Replication areas of at most this many slots are tested slot by slot against their boxes
// (RenderCompartment.slot_lo/hi), cheaper than starting a repLAS query for one or two hits.
NANO_CONST uint NANO_DIRECT_SLOTS = 4u;

NANO_CONST float NANO_TYPICAL_ATOM_DIAMETER = 3.4f;  // Å: carbon's van der Waals diameter

// Per compartment instance (parallel to section "compartment_instances"), rewritten per camera.
// The eye in compartment space as an unevaluated sum hi + lo of floats (computed in double on the
// host): compartment coordinates of a cell reach 4·10^4 Å, where one float ulp is 0.004 Å, so the
// molecule-space ray origin is formed as (hi − T) + lo to keep the hit depth to ~1e-5 Å.
// Directions enter compartment space through the host's double inverse of the instance's linear
// part too, not the driver's WorldToObject: Mesa's lavapipe inverts the whole 4×4 in float, and at a
// camera-relative translation of 5·10^4 Å its linear part is off by 1e-4 (5 Å at that distance).
struct RenderInstance {
  uvec4 base;            // xy: first copy number (lo, hi); z: compartment; w: the flat level's bit of
                         // its triangle 0 (NANO_B_FLAT_TRIANGLES; triangle tl is bit w + tl)
  vec4 eye_hi;           // xyz: float(eye_c); w: reserved
  vec4 eye_lo;           // xyz: float(eye_c − eye_hi); w: reserved
  vec4 from_world[3];    // rows of float(L⁻¹): a camera-relative world vector → compartment space; w: reserved
};

// One nested acceleration structure (an nLAS per molecule type, an mLAS per Wang square and cube, a
// repLAS per compartment with a membrane):
// the device address of its TLAS and where its primitive → record map starts in `orders`.
struct RenderLevel {
  uvec2 address;     // VkDeviceAddress (lo, hi); 0 for an empty tile (no structure)
  uint order_first;  // primitive p names record orders[order_first + p]: an atom index (nLAS) or a
                     // molecule index within its tile (mLAS) or a
                     // replication slot i + W·j (repLAS)
  uint count;        // primitives
};

// Per frame: the camera (camera-relative: the eye is the origin of the µLAS) and level tables.
struct RenderFrame {
  Camera camera;
  uvec4 levels;  // x: first Wang-square entry in `levels` (after one nLAS per molecule type); y: first
                 // cube entry; z: molecule types; w: first two-level atom square (--levels 2)
  vec4 light;    // xyz: unit direction towards the light (world; the shadow light when shadows are on);
                 // w: depth-cue distance (Å, 0 = off)
  uvec4 effects; // x: clipping half-spaces in `clip` (≤ NANO_MAX_CLIP_HALF_SPACES); y: ambient-occlusion
                 // rays; z: sample index (seeds the AO directions); w: first bead level in `levels`
  vec4 effect_parameters;  // x: AO radius (Å); y: time (s); z: jitter amplitude (radians); w: jitter frequency (Hz)
  vec4 lod;       // level of detail: x: a pixel's footprint per Å of distance (2·tan(fov/2) / height);
                  // y: a copy whose atoms (z: their typical diameter, Å) span fewer pixels than this is
                  // drawn as its beads; w: reserved. effects.w holds the first bead level in `levels`.
  vec4 flat_eye;  // the flat level (FlatCopy): xyz: the eye in its space (eye − anchor, from double);
                  // w: 1 when it holds copies, 0 when every compartment instance is traced virtually
  vec4 clip[14];  // camera-relative world half-spaces (unit n, d): a point p stays iff n·p + d ≥ 0 for all
  SceneEffects effect_record;  // the on effects' table parameters, in the package record's layout
  uvec4 pass;     // x: 0 traces the pixels; 1 is the image pass after the last part (effects that read
                  // their neighbours' hits, EffectDeclaration::image_pass); yzw: reserved
};
NANO_CONST uint NANO_MAX_CLIP_HALF_SPACES = 14u;  // 8 planes + the 6 faces of the clip box

// The flat level (runtime/render/flat_level.hpp): the membrane copies of the triangles nearest the
// eye that fit a memory budget, one TLAS instance each over its molecule type's nLAS BLAS, traced as
// explicit instancing traces (one query, atom candidates); the µLAS skips those triangles' prisms
// (a bit per triangle at RenderInstance.base.w). Per TLAS instance (its custom index names it): the
// copy's identity as the virtual path reports it (PixelHit).
struct FlatCopy {
  uint compartment_instance;
  uint element;        // membrane: triangle (section index); core: box linear index
  uint kind;           // 0 membrane, 1 core (PixelHit.kind)
  uint instance;       // the molecule within its Wang square or cube
  ivec4 cell;          // membrane: (a, b, 0, 0); core: (i, j, k, 0)
  uint number_lo;      // copy number
  uint number_hi;
  uint molecule_type;
  uint reserved;
};

// What a core-grid BOUNDARY box keeps, one word per record of section boundary_boxes
// (runtime-derived: runtime/render/kept_boxes.cpp): a box holding the boxes of the molecules its
// keep-mask keeps, in the box's own frame (core_box_min at the origin), on a grid of 31 steps over
// [−B, 2B] (B the box edge; molecules reach at most one box beyond their own) — 5 bits a corner
// coordinate, lo x, y, z then hi x, y, z from bit 0 — and bit 30 set when the mask keeps anything.
// Near a membrane the kept molecules fill one side of the box: a ray that meets the box's reach only
// before them (often at the membrane's hit) skips its mLAS query. 4 bytes a record: the red blood
// cell has ~490,000 of them.
NANO_CONST uint NANO_KEPT_ANY = 0x40000000u;
NANO_CONST float kKeptSteps = 31.0f;

// The kept box of word `k` for boxes of edge B; false when the mask keeps nothing.
NANO_FN bool kept_box_unpack(uint k, float B, NANO_OUT(vec3) lo, NANO_OUT(vec3) hi) {
  float unit = 3.0f * B / kKeptSteps;
  lo = vec3(-B) + vec3(uvec3(k, k >> 5u, k >> 10u) & uvec3(31u)) * unit;
  hi = vec3(-B) + vec3(uvec3(k >> 15u, k >> 20u, k >> 25u) & uvec3(31u)) * unit;
  return (k & NANO_KEPT_ANY) != 0u;
}

NANO_END

#ifdef __cplusplus
#include <cstddef>
static_assert(sizeof(nano::gpu::RenderCompartment) == 128 && offsetof(nano::gpu::RenderCompartment, core_skip) == 112);
static_assert(sizeof(nano::gpu::RenderInstance) == 96 && offsetof(nano::gpu::RenderInstance, from_world) == 48);
static_assert(sizeof(nano::gpu::RenderLevel) == 16);
static_assert(sizeof(nano::gpu::Camera) == 80);
static_assert(sizeof(nano::gpu::RenderFrame) == 672);
static_assert(sizeof(nano::gpu::FlatCopy) == 48);
static_assert(sizeof(nano::gpu::PixelHit) == 48 && offsetof(nano::gpu::PixelHit, cell) == 16 &&
              offsetof(nano::gpu::PixelHit, instance) == 32);
#endif
#endif
