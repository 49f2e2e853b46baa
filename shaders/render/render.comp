#version 460
// The Nanouniverse renderer: one invocation per pixel, nested ray queries over three levels of
// acceleration structures (µLAS → mLAS → nLAS), every molecule placed on the fly by the placement
// math of shaders/shared/ — the very functions the CPU oracle (runtime/oracle/) runs.
//
//  µLAS: one TLAS over compartment instances (camera-relative transforms); per compartment a BLAS of
//        prism AABBs (one per triangle that owns molecules, Morton-sorted) plus one AABB around the
//        core grid. A candidate yields the compartment-space ray (t is the world t).
//  shell: exact ray–prism test (its interval bounds every query below), then the tiles of the
//        triangle's replication area the ray meets (a repLAS query, or slab tests of each slot's box
//        for areas of ≤ NANO_DIRECT_SLOTS slots): tile-space ray by M1⁻¹, the Wang square's mLAS
//        (molecule boxes widened so they contain the true placement, runtime/placement/membrane_distortion.hpp),
//        ownership and seam rule (membrane_keeps_copy) before the true placement M2
//        (chart_membrane_molecule), molecule-space ray, the type's nLAS, exact ray–sphere.
//  core: 3D-DDA over the grid widened by one box; a cell with no live box within one step leaves the
//        largest empty block around it in one step (skip levels, shared/core_skip.h); at every other
//        cell the boxes within one step (a molecule reaches at most one box beyond its own),
//        occupancy and keep-masks, the cube's mLAS, nLAS, ray–sphere. The walk stops once a cell
//        starts beyond the best hit.
// t_max shrinks across all levels: the best t is tracked here and handed to outer queries with
// rayQueryGenerateIntersectionEXT. Hit rule (as the oracle): the smallest root t ≥ 0.
#extension GL_EXT_ray_query : require
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_flags_primitive_culling : require
#include "shared/bindings.h"
#include "shared/package_records.h"
#include "shared/render_scene.h"
#include "shared/tile_mapper.h"
#include "shared/shell_prism.h"
#include "shared/render_membrane_filter.h"
#include "shared/grid_dda.h"
#include "shared/core_skip.h"
#include "shared/ray_sphere.h"
#include "shared/copy_number.h"
#include "shared/effects.h"
#include "shared/ray_counters.h"
#include "shared/medium.h"

// Every acceleration structure here holds boxes only (atoms, molecules, tiles, prisms, copies): with
// triangles skipped by a constant flag the driver compiles no triangle test into the traversals.
const uint kAabbOnly = gl_RayFlagsSkipTrianglesEXT;

layout(local_size_x = NANO_WORKGROUP_SIZE, local_size_y = NANO_WORKGROUP_SIZE) in;

// 0: the prism's AABB is the only test (no exact ray–prism): cheaper test, more candidates.
layout(constant_id = NANO_SPEC_EXACT_PRISM) const bool kExactPrism = true;
// 1: the replication area is one query over a repLAS of its tile boxes; 0: every slot is queried.
layout(constant_id = NANO_SPEC_REPLICATION_LAS) const bool kReplicationLas = true;
// 0: no replication area of the package has more than NANO_DIRECT_SLOTS slots, so every area is
// walked by its slots' boxes and no repLAS is ever queried: its traversal is not compiled (a sixth
// of the default pipeline's traversals; the bundled virion's areas are 2×2).
layout(constant_id = NANO_SPEC_LARGE_REPLICATION_AREAS) const bool kLargeAreas = true;
const bool kRepLasWalk = kReplicationLas && kLargeAreas;
// 1: the paper's two-level membrane: every atom of a Wang square in one BLAS, placed in tile space by
// the affine M1 (an approximation of the true placement that verify measures); 0: mLAS → nLAS.
layout(constant_id = NANO_SPEC_TWO_LEVEL) const bool kTwoLevel = false;
// Precision knob (bench): 7: every ray enters compartment space through the host's double
// computation (RenderInstance: the eye as a two-float sum, the inverse linear part) — false: the
// driver's float WorldToObject; 8: the µLAS in world coordinates with the ray from the world eye —
// false: camera-relative.
layout(constant_id = NANO_SPEC_EYE_FROM_HOST) const bool kEyeFromHost = true;
layout(constant_id = NANO_SPEC_WORLD_SPACE_ULAS) const bool kWorldSpaceUlas = false;
// Scene effects (runtime/render/effects.hpp), each compiled in only when on: a specialization
// constant that is false removes the effect's code before the driver compiles the pipeline. The
// NANO_NO_EFFECTS build of this file (render_no_effects) has no effect code at all, to measure that
// claim (`nanoview bench --effects`).
// The flat level (runtime/render/flat_level.hpp): the membrane copies of the triangles nearest the
// eye, one TLAS instance each, traced in one query before the µLAS, which skips those triangles.
layout(constant_id = NANO_SPEC_FLAT) const bool kFlat = false;
// The scene's medium is traced (it has one, and it is shown): the walk of trace_medium.
layout(constant_id = NANO_SPEC_MEDIUM) const bool kMedium = false;
// Some molecule type is hidden (--hide): its levels read as empty, and candidates of its type are
// dropped at once.
layout(constant_id = NANO_SPEC_HIDDEN_TYPES) const bool kHiddenTypes = false;
#ifdef NANO_NO_EFFECTS
const bool kClipping = false;
const bool kJitter = false;
const bool kAmbientOcclusion = false;
const bool kShadows = false;
const bool kOutlines = false;
const bool kFog = false;
const bool kCounters = false;
const bool kLod = false;
#else
layout(constant_id = NANO_SPEC_CLIPPING) const bool kClipping = false;         // frame.clip half-spaces, per atom centre
layout(constant_id = NANO_SPEC_JITTER) const bool kJitter = false;           // protein jitter (frame.effect_parameters)
layout(constant_id = NANO_SPEC_AMBIENT_OCCLUSION) const bool kAmbientOcclusion = false; // frame.effects.y short rays per pixel
layout(constant_id = NANO_SPEC_SHADOWS) const bool kShadows = false;          // one shadow ray towards frame.light
layout(constant_id = NANO_SPEC_OUTLINES) const bool kOutlines = false;        // contours, in the image pass
layout(constant_id = NANO_SPEC_FOG) const bool kFog = false;                  // depth cueing, in the image pass
// Work counters per pixel (shared/ray_counters.h, `nanoview bench --counters`).
layout(constant_id = NANO_SPEC_COUNTERS) const bool kCounters = false;
// Level of detail: copies whose atoms span less than frame.lod.y pixels are drawn as their beads.
layout(constant_id = NANO_SPEC_LOD) const bool kLod = false;
#endif

layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_ULAS) uniform accelerationStructureEXT ulas;
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_MOLECULES, std430) readonly buffer Molecules { MoleculeType molecules[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_ATOMS, std430) readonly buffer Atoms { Atom atoms[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_TILES2D, std430) readonly buffer Squares { Tile2D squares[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_TILES3D, std430) readonly buffer Cubes { Tile3D cubes[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_INSTANCES, std430) readonly buffer Instances { MoleculeInstance instances[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_RECIPES, std430) readonly buffer Recipes { Recipe recipes[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_RECIPE_INDICES, std430) readonly buffer RecipeIndices { uint recipe_indices[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_MESHES, std430) readonly buffer Meshes { Mesh meshes[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_VERTEX_POSITIONS, std430) readonly buffer Positions { vec4 positions[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_VERTEX_NORMALS, std430) readonly buffer Normals { vec4 normals[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_VERTEX_UVS, std430) readonly buffer Uvs { vec2 uvs[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_TRIANGLES, std430) readonly buffer Triangles { Triangle triangles[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_TRIANGLE_SHELLS, std430) readonly buffer Shells { TriangleShell shells[]; };  // offsets of the shell mode
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_COMPARTMENTS, std430) readonly buffer Compartments { Compartment compartments[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_OCCUPANCY, std430) readonly buffer Occupancy { uint occupancy_words[]; };  // bytes, 4 a word
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_BOUNDARY_BOXES, std430) readonly buffer BoundaryBoxes { BoundaryBox boundary_boxes[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_MASK_WORDS, std430) readonly buffer MaskWords { uint mask_words[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_RENDER_COMPARTMENTS, std430) readonly buffer RenderCompartments { RenderCompartment render_compartments[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_RENDER_INSTANCES, std430) readonly buffer RenderInstances { RenderInstance render_instances[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_LEVELS, std430) readonly buffer Levels { RenderLevel levels[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_ORDERS, std430) readonly buffer Orders { uint orders[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_TRIANGLE_DROPS, std430) readonly buffer TriangleDropRanges { TriangleDrops triangle_drops[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_DROPPED_COPIES, std430) readonly buffer DroppedCopies { uint dropped_copies[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_BEADS, std430) readonly buffer Beads { Bead beads[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_FLAT_TLAS) uniform accelerationStructureEXT flat_tlas;
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_FLAT_COPIES, std430) readonly buffer FlatCopies { FlatCopy flat_copies[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_FLAT_TRIANGLES, std430) readonly buffer FlatTriangles { uint flat_triangles[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_CORE_SKIP, std430) readonly buffer CoreSkip { uint core_skip_words[]; };  // 8 cells a word
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_KEPT_BOXES, std430) readonly buffer KeptBoxes { uint kept_boxes[]; };  // parallel to boundary_boxes
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_MEDIUM, std430) readonly buffer MediumSection { Medium medium[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_EXCLUSION_FIELDS, std430) readonly buffer ExclusionFields { ExclusionField exclusion_fields[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_EXCLUSION_VALUES, std430) readonly buffer ExclusionValues { float exclusion_values[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_MEDIUM_INSTANCES, std430) readonly buffer MediumInstances { MediumInstance medium_instances[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_RENDER_MEDIUM, std430) readonly buffer RenderMediumRecord { RenderMedium render_medium; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_EXCLUSION_TLAS) uniform accelerationStructureEXT exclusion_tlas;
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_FRAME, std430) readonly buffer Frame { RenderFrame frame; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_HITS, std430) writeonly buffer Hits { PixelHit hits[]; };
// The same buffer as the image pass reads it; the tracing code keeps its write-only view.
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_HITS, std430) readonly buffer FinishedHits { PixelHit finished_hits[]; };
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_COLOURS, std430) buffer Colours { uint colours[]; };  // RGBA8, sRGB (the image pass reads and mixes)
layout(set = NANO_DESCRIPTOR_SET, binding = NANO_B_COUNTERS, std430) writeonly buffer Counters { uint counters[]; };

// The frame may be traced in parts (a viewer interleaves them with input): this dispatch's first pixel.
layout(push_constant) uniform Part { uvec2 origin; } part;

uint ray_counts[NANO_RAY_COUNTER_COUNT];  // this pixel's work (kCounters only)
void count_work(uint counter) {
  if (kCounters) ray_counts[counter] += 1u;
}

// The best hit so far. Ids follow PixelHit (shared/camera.h).
float best_t;
PixelHit best;
vec3 best_normal_c;      // compartment-space unit normal at the hit
mat4x3 best_to_world;    // compartment → camera-relative world of the hit's instance
uint best_type;          // molecule type of the hit atom

vec3 eye_lo;  // low part of the compartment-space eye (RenderInstance.eye_lo) of the instance being traced
vec4 clip_c[NANO_MAX_CLIP_HALF_SPACES];  // the clipping half-spaces in the space of the instance being traced

// Each level's traversal in a file of its own (docs/layout.md, "The files an acceleration level
// touches"), reading the declarations above. In this order: a file calls only what the files before it
// define (trace_element, called by the membrane and core walks, is declared in element.glsl).
#include "render/clip.glsl"
#include "render/atoms.glsl"
#include "render/sections.glsl"
#include "render/element.glsl"
#include "render/flat.glsl"
#include "render/membrane.glsl"
#include "render/core.glsl"
#include "render/element_trace.glsl"
#include "render/medium.glsl"
#include "render/ulas.glsl"
#include "render/image.glsl"

void main() {
  Camera cam = frame.camera;
  uvec2 px = gl_GlobalInvocationID.xy + part.origin;
  if (px.x >= cam.size.x || px.y >= cam.size.y) return;
  if (kImagePass && frame.pass.x != 0u) {
    image_pass(px, px.y * cam.size.x + px.x);
    return;
  }
  vec3 d = camera_ray_direction(cam, px.x, px.y);
  if (kCounters)
    for (uint k = 0u; k < NANO_RAY_COUNTER_COUNT; ++k) ray_counts[k] = 0u;

  uint index = px.y * cam.size.x + px.x;
  vec3 origin = kWorldSpaceUlas ? frame.camera.position.xyz : vec3(0.0);
  // Every ray of the pixel — primary, then the shadow ray, then the AO rays — goes through the one
  // call of trace_scene below (one inlined traversal, not one per kind of ray).
  uint shadow_rays = kShadows ? 1u : 0u;
  uint ao_rays = kAmbientOcclusion ? max(frame.effects.y, 1u) : 0u;
  uint ao_seed = kAmbientOcclusion ? effect_hash(index ^ effect_hash(frame.effects.z + 0x68bc21ebu)) : 0u;
  PixelHit hit;
  uint hit_type = 0u;
  float t = 0.0;
  vec3 n = vec3(0.0);
  vec3 n_view = vec3(0.0);
  vec3 p = vec3(0.0);
  vec3 light = frame.light.xyz;
  float lambert = 0.0;
  uint open = 0u;
  for (uint r = 0u; r < 1u + shadow_rays + ao_rays; ++r) {
    vec3 ray_origin = origin;
    vec3 ray_direction = d;
    float t_max = placement_inf();
    if (r > 0u) ray_origin = p;
    if (r > 0u && r <= shadow_rays) {
      if (!(lambert > 0.0)) continue;
      ray_direction = light;
    } else if (r > 0u) {
      uint h = effect_hash(ao_seed + 2u * (r - 1u - shadow_rays));
      ray_direction = cosine_hemisphere(n_view, effect_unit(h), effect_unit(effect_hash(h + 1u)));
      t_max = max(frame.effect_parameters.x, frame.effect_record.ao_radius_pixels * frame.lod.x * t);
    }
    bool blocked = trace_scene(ray_origin, ray_direction, t_max, r == 0u);
    if (r == 0u) {
      hit = best;
      hit_type = best_type;
      if (!blocked) break;
      t = best_t;
      hit.depth = t;
      n = normalize(mat3(best_to_world) * best_normal_c);
      lambert = abs(dot(n, light));
      // Secondary rays leave the side of the sphere the camera sees.
      n_view = dot(n, d) > 0.0 ? -n : n;
      p = offset_ray_origin(origin + t * d, n_view);
      if (kShadows) lambert = max(dot(n_view, light), 0.0);
    } else if (r <= shadow_rays) {
      if (blocked) lambert = 0.0;
    } else if (!blocked) {
      ++open;
    }
  }

  vec3 colour = vec3(1.0);  // background
  if (hit.atom != kNoHit) {
    vec3 base = molecules[hit_type].colour.rgb;
    float facing = abs(dot(n, d));
    float ambient = kAmbientOcclusion ? float(open) / float(ao_rays) : 1.0;
    vec3 lit = base * ((0.25 + 0.2 * facing) + 0.55 * lambert) * (0.4 + 0.6 * ambient);
    float cue = frame.light.w > 0.0 ? exp(-t / frame.light.w) : 1.0;
    colour = mix(vec3(1.0), lit, 0.35 + 0.65 * cue);
  }
  hits[index] = hit;
  colours[index] = rgba8_from_bytes(srgb_from_linear(colour) * 255.0);
  if (kCounters && (index + 1u) * NANO_RAY_COUNTER_COUNT <= uint(counters.length()))
    for (uint k = 0u; k < NANO_RAY_COUNTER_COUNT; ++k) counters[index * NANO_RAY_COUNTER_COUNT + k] = ray_counts[k];
}
