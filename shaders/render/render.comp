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

// The jittered placement of copy `number` (kJitter only).
Affine3 jittered(Affine3 m, uvec2 number) {
  vec4 p = frame.effect_parameters;
  return jitter_placement(m, jitter_rotation(number, p.y, p.z, p.w));
}

// A hidden type (kHiddenTypes): GpuScene::set_visibility emptied its level.
bool type_hidden(uint type) { return kHiddenTypes && levels[type].count == 0u; }

// The exact difference a − b of two floats as an unevaluated pair hi + lo (Knuth's TwoSum; `precise`
// keeps the compiler from reassociating it away or fusing it).
void two_diff(vec3 a, vec3 b, out vec3 hi, out vec3 lo) {
  precise vec3 s = a - b;
  precise vec3 bb = s - a;
  precise vec3 err = (a - (s - bb)) - (b + bb);
  hi = s;
  lo = err;
}

// Nearest atom of molecule type `type` placed by `m` (compartment space; its translation exactly
// m.translation + translation_lo) on the ray (o, d) within [t_lo, best_t] (t_lo: where the copy can
// begin along the ray, 0 when unknown); o is the compartment-space eye (high part, eye_lo the low).
// Updates best_t, best.atom and best_normal_c; true iff it found a nearer atom.
// The ray enters molecule space rebased to where it can first meet the copy (t0): the eye − copy
// vector kept exact as a float pair and t0·d added with its rounding error, so the molecule-space
// origin is as precise near a copy 4·10^5 Å away as near the eye (a float origin that far is off by
// 0.03 Å: another atom than explicit instancing's on ~1 % of a far view's pixels).
bool trace_molecule(uint type, Affine3 m, vec3 translation_lo, vec3 o, vec3 d, float t_lo) {
  vec3 s_hi;
  vec3 s_lo;
  two_diff(o, m.translation, s_hi, s_lo);
  s_lo += eye_lo - translation_lo;
  float dd = dot(d, d);
  float t0 = max(0.0, -dot(s_hi, d) / dd - molecules[type].aabb_min.w / sqrt(dd));
  precise vec3 p_hi = t0 * d;
  precise vec3 p_lo = fma(vec3(t0), d, -p_hi);
  precise vec3 rebased = (s_hi + p_hi) + (s_lo + p_lo);
  mat3 rt = transpose(m.linear);
  vec3 om = rt * rebased;
  vec3 dm = rt * d;
  // Beads when an atom of the copy, at the copy's distance, spans fewer than frame.lod.y pixels.
  bool coarse = kLod && frame.lod.z < frame.lod.y * frame.lod.x * length(m.translation - o);
  RenderLevel level = levels[coarse ? frame.effects.w + type : type];
  if (level.count == 0u) return false;
  bool found = false;
  float near_lo = max(t_lo - t0, 0.0);  // no hit lies before t0: it is where the copy's sphere begins
  float near_best = best_t - t0;          // best_t in the rebased ray's parameter, kept there
  count_work(NANO_RC_NLAS_QUERIES);
  rayQueryEXT q;
  rayQueryInitializeEXT(q, accelerationStructureEXT(level.address), kAabbOnly, 0xFF, om, near_lo, dm, near_best);
  while (rayQueryProceedEXT(q)) {
    count_work(NANO_RC_NLAS_CANDIDATES);
    uint p = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false));
    if (p >= level.count) continue;
    uint a = orders[level.order_first + p];
    vec4 cr = coarse ? beads[a].centre_radius : atoms[a].centre_radius;
    float tn;
    float tf;
    count_work(NANO_RC_SPHERE_TESTS);
    if (!sphere_intersect(om, dm, cr.xyz, cr.w, tn, tf)) continue;
    float t = tn >= -t0 ? tn : tf;  // the eye inside the atom: its far side
    if (!(t >= -t0) || !(t < near_best)) continue;
    // An atom is clipped whole, by its centre: never cut in half.
    if (kClipping && clip_removes_point(m.linear * cr.xyz + m.translation)) continue;
    near_best = t;
    best_t = t0 + t;
    best.atom = coarse ? beads[a].atom : a;
    best_type = type;
    best_normal_c = m.linear * normalize(om + t * dm - cr.xyz);
    found = true;
    if (t >= near_lo) rayQueryGenerateIntersectionEXT(q, t);  // a hit must lie in the query's range
  }
  return found;
}

uint recipe_cell(uint recipe, ivec3 cell) {
  Recipe r = recipes[recipe];
  ivec3 dims = ivec3(r.dims.xyz);
  ivec3 w = ((cell % dims) + dims) % dims;  // recipes wrap in every direction
  return recipe_indices[r.first_index + uint(w.x) + r.dims.x * (uint(w.y) + r.dims.y * uint(w.z))];
}

// One µLAS candidate is a prism (its membrane copies, tile by tile of the triangle's replication area)
// or a core grid (its soluble copies, box by box). Both are walked by one loop that yields elements —
// a replication slot or a core-grid box — and every element is traced by the one mLAS query of
// trace_element, which calls the one nLAS query of trace_molecule. Each ray-query loop thus appears
// once in the shader: a driver inlines every call, and a traversal loop is the bulk of the compiled
// code (issue #26: 11 to 22 inlined loops took 9–29 s to compile on lavapipe).
const uint kWalkSlotBoxes = 0u;  // a small replication area: each slot's box by a slab test
const uint kWalkRepLas = 1u;     // the slots the area's repLAS query meets
const uint kWalkAllSlots = 2u;   // every slot (no repLAS: bench knob)

// What a prism's slots share: the triangle, its chart, the ray's part inside the prism [t_lo, t_hi]
// (where every copy the prism owns lies) and the replication area.
struct ShellWalk {
  MembraneTriangle mt;
  TriangleChart chart;
  float t_lo;
  float t_hi;
  ivec2 origin;  // the area's first tile
  ivec2 extent;  // its slots, x by y
  uint mode;     // kWalkSlotBoxes, kWalkRepLas or kWalkAllSlots
  vec3 ot;       // the ray in the origin tile's space (slot boxes, repLAS)
  vec3 dt;
  uint squares;  // the triangle's distortion class: its first square mLAS, relative to frame.levels.x
  mat3 lift;             // the smooth surface's lift (chart_smooth_lift_coefficients); zero: not sheared
  mat3 lift_directions;  // chart_lift_directions
};

// Where the copies of one element can be hit: its mLAS (`entry` in `levels`) and its tile's first
// molecule instance, the ray in the tile's space on [q_lo, q_hi], and what the copies' placement needs.
struct ElementQuery {
  uint entry;
  uint first;
  vec3 ot;
  vec3 dt;
  float q_lo;
  float q_hi;
  vec2 g;        // membrane: the tile's UV origin
  vec3 box_min;  // core: the box's corner
  uint mask;     // core: the boundary box's keep-mask
};

// Defined below, after both levels' element queries it calls; declared here so the membrane and core
// walks, which come before it, can call it.
bool trace_element(uint inst, uint ci, Compartment c, RenderCompartment rc, bool membrane, uint tl, ShellWalk w,
                   uint slot_or_box, ivec3 cell, vec3 o, vec3 d);

bool triangle_flattened(uint bit) {
  return (bit >> 5) < uint(flat_triangles.length()) && ((flat_triangles[bit >> 5] >> (bit & 31u)) & 1u) != 0u;
}

// A candidate of the flat level (a TLAS of copies, each an instance of its molecule type's nLAS BLAS,
// so every candidate is an atom box in molecule space: the ray the hardware transformed, as explicit
// instancing traces): copy `c`, primitive `p`, the molecule-space ray (om, dm) and the copy's
// transforms. True iff it is the nearest hit so far (ids recorded). Every index read from the level is
// checked against the buffer it names.
bool flat_atom_hit(uint c, uint p, vec3 om, vec3 dm, mat4x3 object_to_world, mat4x3 world_to_object) {
  count_work(NANO_RC_FLAT_CANDIDATES);
  if (c >= uint(flat_copies.length())) return false;
  FlatCopy fc = flat_copies[c];
  if (fc.molecule_type >= frame.levels.z) return false;
  RenderLevel level = levels[fc.molecule_type];
  if (p >= level.count) return false;
  uint a = orders[level.order_first + p];
  vec4 cr = atoms[a].centre_radius;
  float tn;
  float tf;
  count_work(NANO_RC_SPHERE_TESTS);
  if (!sphere_intersect(om, dm, cr.xyz, cr.w, tn, tf)) return false;
  float t = tn >= 0.0 ? tn : tf;
  if (!(t >= 0.0) || !(t < best_t)) return false;
  // An atom is clipped whole, by its centre (clip_c is in the level's space: see trace_scene).
  if (kClipping && clip_removes_point(object_to_world * vec4(cr.xyz, 1.0))) return false;
  best_t = t;
  best.compartment_instance = fc.compartment_instance;
  best.element = fc.element;
  best.kind = fc.kind;
  best.cell = fc.cell;
  best.instance = fc.instance;
  best.atom = a;
  best.copy_number_lo = fc.number_lo;
  best.copy_number_hi = fc.number_hi;
  best_type = fc.molecule_type;
  // World normal by the inverse transpose (an instance may scale); the hit's "compartment" is the world.
  best_normal_c = normalize(transpose(mat3(world_to_object)) * (om + t * dm - cr.xyz));
  best_to_world = mat4x3(1.0);
  return true;
}

// True iff the baker listed the copy `key` (membrane_copy_key) of the triangle (dropped, or an
// alternate shown): binary search over its strictly ascending keys (the validator checks the order
// and the range).
bool membrane_copy_listed(MembraneTriangle mt, uint key) {
  uint lo = mt.drop_first;
  uint hi = mt.drop_first + mt.drop_count;
  while (lo < hi) {
    uint mid = (lo + hi) >> 1;
    if (dropped_copies[mid] < key) lo = mid + 1u; else hi = mid;
  }
  return lo < mt.drop_first + mt.drop_count && dropped_copies[lo] == key;
}

// Two-level membrane tile: atoms straight from the square's atom BLAS, intersected as spheres in tile
// space (ellipsoids in the world under M1's stretch and shear), with the molecule's ownership and seam
// rule decided at its true centre.
bool trace_atom_tile(uint inst, uint ci, uint tl, MembraneTriangle mt, TriangleChart chart, ivec2 cell, uint tile,
                     uint slot, vec3 o, vec3 d) {
  Compartment c = compartments[ci];
  RenderCompartment rc = render_compartments[ci];
  RenderLevel level = levels[frame.levels.w + tile];
  if (level.count == 0u) return false;
  float s_over_S = rc.membrane.y;
  vec2 g = replication_tile_uv(cell, rc.membrane.x);
  vec3 ot;
  vec3 dt;
  chart_tile_inverse_ray(chart, g, s_over_S, o, d, ot, dt);
  uint first = squares[tile].first_instance;
  bool found = false;
  count_work(NANO_RC_NLAS_QUERIES);
  rayQueryEXT q;
  rayQueryInitializeEXT(q, accelerationStructureEXT(level.address), kAabbOnly, 0xFF, ot, 0.0, dt, best_t);
  while (rayQueryProceedEXT(q)) {
    count_work(NANO_RC_NLAS_CANDIDATES);
    uint p = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false));
    if (p >= level.count) continue;
    uint m = orders[level.order_first + 2u * p];
    uint a = orders[level.order_first + 2u * p + 1u];
    MoleculeInstance mi = instances[first + m];
    if (type_hidden(mi.molecule_type)) continue;
    vec4 cr = atoms[a].centre_radius;
    vec3 centre = mi.position.xyz + quat_rotate(mi.rotation, cr.xyz);
    float tn;
    float tf;
    count_work(NANO_RC_SPHERE_TESTS);
    if (!sphere_intersect(ot, dt, centre, cr.w, tn, tf)) continue;
    float t = tn >= 0.0 ? tn : tf;
    if (!(t >= 0.0) || !(t < best_t)) continue;
    vec2 uv_m = chart_molecule_uv(g, s_over_S, mi.position.xyz);
    if (!membrane_keeps_copy(mt, uv_m, chart_position(chart, uv_m), molecules[mi.molecule_type].aabb_min.w)) {
      count_work(NANO_RC_OWNERSHIP_REJECTS);
      continue;
    }
    if (!membrane_copy_listed_shows(membrane_copy_listed(mt, membrane_copy_key(slot, m)), mi.flags)) {
      count_work(NANO_RC_LISTED_REJECTS);
      continue;
    }
    best_t = t;
    best.atom = a;
    best_type = mi.molecule_type;
    // The ellipsoid's normal: the tile-space sphere normal through the transpose of M1⁻¹.
    best_normal_c = normalize(transpose(chart_tile_frame_inverse_linear(chart, s_over_S)) * (ot + t * dt - centre));
    best.compartment_instance = inst;
    best.element = meshes[c.mesh].first_triangle + tl;
    best.kind = 0u;
    best.cell = ivec4(cell, 0, 0);
    best.instance = m;
    uvec2 number = copy_number_membrane(render_instances[inst].base.xy, tl, c.replication_width * c.replication_height,
                                        slot, rc.counts.x, m);
    best.copy_number_lo = number.x;
    best.copy_number_hi = number.y;
    found = true;
    rayQueryGenerateIntersectionEXT(q, t);
  }
  return found;
}

// The prism of triangle `tl` (local index in the mesh) of compartment `ci`: false when the ray misses
// it or clipping removes all it holds.
bool shell_walk_begin(uint ci, uint tl, vec3 o, vec3 d, out ShellWalk w) {
  Compartment c = compartments[ci];
  RenderCompartment rc = render_compartments[ci];
  Mesh mesh = meshes[c.mesh];
  uint t = mesh.first_triangle + tl;
  Triangle tri = triangles[t];
  uint f = mesh.first_vertex;
  vec3 p0 = positions[f + tri.v0].xyz;
  vec3 p1 = positions[f + tri.v1].xyz;
  vec3 p2 = positions[f + tri.v2].xyz;
  vec3 n0 = normals[f + tri.v0].xyz;
  vec3 n1 = normals[f + tri.v1].xyz;
  vec3 n2 = normals[f + tri.v2].xyz;
  TriangleShell sh = shells[t];
  ShellOffsets off;
  off.h_plus = sh.h_plus;
  off.h_minus = sh.h_minus;
  off.side = sh.side_offset;
  Prism pr = shell_prism_make(p0, p1, p2, n0, n1, n2, off);  // compiled out when neither test below is on
  count_work(NANO_RC_PRISM_TESTS);
  // The ray's part inside the prism, widened by a margin for rounding (jitter moves copies out).
  w.t_lo = 0.0;
  w.t_hi = best_t;
  if (kExactPrism) {
    PrismInterval iv;
    if (!prism_intersect(pr, o, d, 0.0, best_t, iv)) return false;
    if (!kJitter && !kTwoLevel) {
      float margin = 0.05 + 1e-5 * iv.t_exit;
      w.t_lo = max(iv.t_enter - margin, 0.0);
      w.t_hi = iv.t_exit + margin;
    }
  }
  count_work(NANO_RC_PRISMS_ENTERED);
  if (kClipping) {
    // µLAS-level trivial reject: every molecule the prism owns lies in the convex hull of its six
    // corners (bilinear walls included), so a hull wholly outside one half-space has nothing to show.
    vec3 lo = pr.v[0];
    vec3 hi = pr.v[0];
    for (int k = 1; k < 6; ++k) {
      lo = min(lo, pr.v[k]);
      hi = max(hi, pr.v[k]);
    }
    if (clip_removes_box(lo, hi)) return false;
  }
  w.mt.p0 = p0;
  w.mt.p1 = p1;
  w.mt.p2 = p2;
  w.mt.t0 = uvs[f + tri.v0];
  w.mt.t1 = uvs[f + tri.v1];
  w.mt.t2 = uvs[f + tri.v2];
  w.mt.seam_edges = sh.seam_edges;
  // A package without drops gets a zero record per triangle from the loader (levels/sections.cpp).
  TriangleDrops td = triangle_drops[t];
  w.mt.drop_first = td.first;
  w.mt.drop_count = td.count;
  w.chart = chart_make(p0, p1, p2, w.mt.t0, w.mt.t1, w.mt.t2, n0, n1, n2);
  uint cls = orders[rc.core_skip.y + tl];
  w.squares = cls & ~NANO_LIFT_UNSHEARED;
  w.lift = chart_smooth_lift_coefficients(w.chart, (cls & NANO_LIFT_UNSHEARED) != 0u ? 0.0 : c.scales.w);
  w.lift_directions = chart_lift_directions(w.chart, rc.membrane.y);
  float s = rc.membrane.x;
  vec2 uv_min = min(w.mt.t0, min(w.mt.t1, w.mt.t2));
  vec2 uv_max = max(w.mt.t0, max(w.mt.t1, w.mt.t2));
  w.origin = replication_origin(uv_min, s);
  w.extent = min(replication_extent(uv_min, uv_max, s), ivec2(c.replication_width, c.replication_height));
  bool rep = kReplicationLas && rc.span.w != NANO_NO_INDEX;
  w.mode = !rep ? kWalkAllSlots : !kLargeAreas || uint(w.extent.x * w.extent.y) <= NANO_DIRECT_SLOTS ? kWalkSlotBoxes : kWalkRepLas;
  // Every tile of the triangle shares M1's linear part: slot (i, j)'s box is the origin tile's moved
  // by (i·S, j·S, 0) in the origin tile's space.
  chart_tile_inverse_ray(w.chart, replication_tile_uv(w.origin, s), rc.membrane.y, o, d, w.ot, w.dt);
  return true;
}

// Replication slot `cell` (tile `tile` of the membrane recipe) of the prism walk w.
void membrane_element_query(RenderCompartment rc, ShellWalk w, uint tile, ivec2 cell, vec3 o, vec3 d, inout ElementQuery e) {
  float s_over_S = rc.membrane.y;
  e.entry = frame.levels.x + w.squares + tile;  // the mLAS of the triangle's distortion class
  e.first = squares[tile].first_instance;
  e.g = replication_tile_uv(cell, rc.membrane.x);
  chart_tile_inverse_ray(w.chart, e.g, s_over_S, o, d, e.ot, e.dt);
  // Its mLAS boxes stand on the tile's lift plane, not on the facet (levels/membrane.cpp, square_boxes).
  vec2 centre = vec2(rc.membrane.z);
  chart_lift_shear_ray(chart_smooth_lift_plane(w.chart, w.lift, w.lift_directions, e.g, s_over_S, centre), centre, e.ot, e.dt);
  e.q_lo = w.t_lo;
  e.q_hi = min(best_t, w.t_hi);
}

// The next slot of the prism walk w's area from `step` on, in order: every one (kWalkAllSlots) or each
// whose box the ray meets (kWalkSlotBoxes). False when none is left.
bool next_slot_in_order(RenderCompartment rc, ShellWalk w, inout uint step, inout ivec2 element) {
  while (step < uint(w.extent.x * w.extent.y)) {
    ivec2 sxy = ivec2(int(step % uint(w.extent.x)), int(step / uint(w.extent.x)));
    ++step;
    if (w.mode == kWalkSlotBoxes) {
      vec3 shift = vec3(float(sxy.x) * rc.slot_lo.w, float(sxy.y) * rc.slot_lo.w, 0.0);
      float tn;
      float tf;
      if (!aabb_intersect(rc.slot_lo.xyz + shift, rc.slot_hi.xyz + shift, w.ot, w.dt, w.t_lo, min(best_t, w.t_hi), tn, tf)) continue;
    }
    element = sxy;
    return true;
  }
  return false;
}

// The membrane copies of prism `prim` of instance `inst` (compartment `ci`) on the ray (o, od): the
// slots of its triangle's replication area the ray meets, each traced by trace_element. False when
// the triangle is in the flat level, the ray misses its prism or it found no nearer hit.
bool trace_prism(uint inst, uint ci, Compartment c, RenderCompartment rc, uint prim, bool use_flat, vec3 o, vec3 od) {
  uint tl = orders[rc.counts.w + prim];
  if (use_flat && triangle_flattened(render_instances[inst].base.w + tl)) return false;  // its copies are in the flat level
  ShellWalk w;
  if (!shell_walk_begin(ci, tl, o, od, w)) return false;
  bool found = false;
  rayQueryEXT area;  // kWalkRepLas: the replication area's tile boxes
  if (kRepLasWalk && w.mode == kWalkRepLas) {
    RenderLevel a = levels[rc.span.w];
    count_work(NANO_RC_REPLAS_QUERIES);
    rayQueryInitializeEXT(area, accelerationStructureEXT(a.address), kAabbOnly, 0xFF, w.ot, w.t_lo, w.dt, min(best_t, w.t_hi));
  }
  uint step = 0u;  // slots walked
  while (true) {
    // The next slot of the area.
    ivec2 element = ivec2(0);
    bool next = false;
    if (kRepLasWalk && w.mode == kWalkRepLas) {
      while (!next && rayQueryProceedEXT(area)) {
        uint p = uint(rayQueryGetIntersectionPrimitiveIndexEXT(area, false));
        RenderLevel a = levels[rc.span.w];
        if (p >= a.count) continue;
        uint slot = orders[a.order_first + p];
        ivec2 sxy = ivec2(int(slot % c.replication_width), int(slot / c.replication_width));
        if (sxy.x >= w.extent.x || sxy.y >= w.extent.y) continue;
        element = sxy;
        next = true;
      }
    } else {
      next = next_slot_in_order(rc, w, step, element);
    }
    if (!next) break;
    count_work(NANO_RC_SLOTS_TRIED);
    uint slot = uint(element.x) + c.replication_width * uint(element.y);
    if (!trace_element(inst, ci, c, rc, true, tl, w, slot, ivec3(replication_tile_index(w.origin, element), 0), o, od)) continue;
    found = true;
    if (kRepLasWalk && w.mode == kWalkRepLas && best_t >= w.t_lo) rayQueryGenerateIntersectionEXT(area, best_t);
  }
  return found;
}

uint occupancy_of(uint byte_index) { return (occupancy_words[byte_index >> 2] >> (8u * (byte_index & 3u))) & 0xFFu; }

// The record of BOUNDARY box `box` in boundary_boxes and kept_boxes (binary search over the
// compartment's sorted records), or NANO_NO_INDEX when the package lists none (the validator makes
// that impossible).
uint boundary_record(Compartment c, uint box) {
  uint lo = c.core_masks.x;
  uint hi = c.core_masks.x + c.core_masks.y;
  while (lo < hi) {
    uint mid = (lo + hi) >> 1;
    if (boundary_boxes[mid].box < box) lo = mid + 1u; else hi = mid;
  }
  if (lo < c.core_masks.x + c.core_masks.y && lo < uint(kept_boxes.length()) && boundary_boxes[lo].box == box) return lo;
  return NANO_NO_INDEX;
}

// Core-grid box `box` (grid cell `cell`): false when the ray misses what the box can hold, clipping
// removes it or it lies outside the compartment.
bool core_element_query(Compartment c, RenderCompartment rc, uint box, ivec3 cell, vec3 o, vec3 d, inout ElementQuery e) {
  uint occ = occupancy_of(c.grid_dims.w + box);
  if (occ == NANO_BOX_OUTSIDE) return false;
  e.box_min = core_box_min(c.grid_min.xyz, vec3(c.grid_min.w), cell);
  float tn;
  float tf;
  if (!aabb_intersect(e.box_min + rc.reach_lo.xyz, e.box_min + rc.reach_hi.xyz, o, d, 0.0, best_t, tn, tf)) return false;
  if (kClipping && clip_removes_box(e.box_min + rc.reach_lo.xyz, e.box_min + rc.reach_hi.xyz)) return false;
  if (occ == NANO_BOX_BOUNDARY) {
    uint record = boundary_record(c, box);
    if (record == NANO_NO_INDEX) return false;
    vec3 kept_lo;
    vec3 kept_hi;
    if (!kept_box_unpack(kept_boxes[record], c.grid_min.w, kept_lo, kept_hi) ||
        !aabb_intersect(e.box_min + kept_lo, e.box_min + kept_hi, o, d, 0.0, best_t, tn, tf))
      return false;
    e.mask = boundary_boxes[record].first_word;
  }
  uint cube = recipe_cell(c.soluble_recipe, cell);
  e.entry = frame.levels.y + cube;
  e.first = cubes[cube].first_instance;
  e.ot = o - e.box_min;
  e.dt = d;
  e.q_lo = 0.0;
  e.q_hi = best_t;
  return true;
}

// The soluble copies of instance `inst`'s core grid (compartment `ci`) on the ray (o, od): its own
// walk (its own mLAS and nLAS loops once compiled), cells in ray order, at each the boxes within one
// step not traced at the cell before. False when it found no nearer hit.
bool trace_core_grid(uint inst, uint ci, Compartment c, RenderCompartment rc, vec3 o, vec3 od) {
  if (rc.span.z == 0u) return false;
  float B = c.grid_min.w;
  if (kClipping && clip_removes_box(c.grid_min.xyz - vec3(B), c.grid_min.xyz + vec3(ivec3(c.grid_dims.xyz) + ivec3(1)) * B)) return false;
  // The grid widened by one box on every side: a molecule reaches at most one box beyond its own,
  // so every point where a copy can be hit lies in a cell of this grid within one step of its box.
  GridDda it;
  dda_init(it, c.grid_min.xyz - vec3(B), vec3(B), ivec3(c.grid_dims.xyz) + ivec3(2), o, od, 0.0, best_t);
  ShellWalk w;  // trace_element's membrane state, unused by a core box
  bool found = false;
  ivec3 dims = ivec3(c.grid_dims.xyz);
  ivec3 cell;
  float ta;
  ivec3 previous = ivec3(-1000000);
  ivec3 cells = dims + ivec3(2);
  while (dda_current(it, cell, ta)) {
    if (ta > best_t) break;  // a cell beyond the best hit ends the walk
    count_work(NANO_RC_CORE_STEPS);
    uint skip_index = rc.core_skip.x + uint(cell.x) + uint(cells.x) * (uint(cell.y) + uint(cells.y) * uint(cell.z));
    uint skip = core_skip_level_in_word(core_skip_words[skip_index >> 3], skip_index);
    if (skip != 0u) {
      // Nothing to trace within one step of any cell of the block: the walk resumes beyond it.
      // `cell`'s own boxes are dead, so it may stand as the cell before for the de-duplication.
      ivec3 block_lo = core_skip_block_lo(cell, skip);
      dda_skip_block(it, block_lo, core_skip_block_hi(block_lo, skip, cells));
    } else {
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            ivec3 ijk = cell - ivec3(1) + ivec3(dx, dy, dz);
            if (any(lessThan(ijk, ivec3(0))) || any(greaterThanEqual(ijk, dims))) continue;
            ivec3 from_previous = abs(ijk - (previous - ivec3(1)));
            if (max(from_previous.x, max(from_previous.y, from_previous.z)) <= 1) continue;
            count_work(NANO_RC_CORE_BOXES);
            uint box = uint(ijk.x) + uint(dims.x) * (uint(ijk.y) + uint(dims.y) * uint(ijk.z));
            if (trace_element(inst, ci, c, rc, false, 0u, w, box, ijk, o, od)) found = true;
          }
    }
    previous = cell;
    dda_advance(it);  // the one step of the walk, after a skip out of the block
  }
  return found;
}

// Copy m (instance mi) of the element placed and numbered: false when the membrane's ownership,
// seam rule or the baker's list rejects it.
bool place_element_copy(uint inst, Compartment c, RenderCompartment rc, bool membrane, uint tl, ShellWalk w,
                        uint slot_or_box, ElementQuery e, uint m, MoleculeInstance mi, out Affine3 placement,
                        out uvec2 number) {
  if (membrane) {
    // Ownership and the seam rule first: they need only the copy's UV (the same chart_molecule_uv
    // the placement computes, so bit-identical), and they reject most candidates before the
    // placement's normal, frame and rotation are computed.
    float s_over_S = rc.membrane.y;
    vec2 uv_m = chart_molecule_uv(e.g, s_over_S, mi.position.xyz);
    if (!membrane_keeps_copy(w.mt, uv_m, chart_position(w.chart, uv_m), molecules[mi.molecule_type].aabb_min.w)) {
      count_work(NANO_RC_OWNERSHIP_REJECTS);
      return false;
    }
    if (!membrane_copy_listed_shows(membrane_copy_listed(w.mt, membrane_copy_key(slot_or_box, m)), mi.flags)) {
      count_work(NANO_RC_LISTED_REJECTS);
      return false;
    }
    placement = chart_membrane_molecule(w.chart, e.g, s_over_S, c.scales.w, mi.position.xyz, mi.rotation, uv_m);
    number = copy_number_membrane(render_instances[inst].base.xy, tl, c.replication_width * c.replication_height,
                                  slot_or_box, rc.counts.x, m);
  } else {
    placement = core_soluble_molecule(e.box_min, mi.position.xyz, mi.rotation);
    number = copy_number_core(render_instances[inst].base.xy, rc.span.xy, slot_or_box, rc.counts.y, m);
  }
  return true;
}

// The copies of one element on the ray (o, d) (compartment space), placed on the fly: membrane copies
// of replication slot `slot_or_box` (tile `cell.xy` of the area, on [w.t_lo, w.t_hi]) of triangle
// `tl`, or soluble copies of core-grid box `slot_or_box` (grid cell `cell`). The element's mLAS
// holds its Wang square's or cube's molecule boxes. Called twice, `membrane` constant at each call:
// the membrane slots and the core boxes each get their own mLAS and nLAS loops once compiled. One
// shared call compiled 20 % faster but traced 8–13 % slower on lavapipe with the same work per pixel
// (docs/bench/compile.md): the core walk, ~150 boxes a pixel on a cell, then paid for the membrane's
// state. `c` and `rc` are compartment `ci`'s records, read once per µLAS candidate by the caller.
bool trace_element(uint inst, uint ci, Compartment c, RenderCompartment rc, bool membrane, uint tl, ShellWalk w,
                   uint slot_or_box, ivec3 cell, vec3 o, vec3 d) {
  ElementQuery e;
  e.g = vec2(0.0);
  e.box_min = vec3(0.0);
  e.mask = NANO_NO_INDEX;
  if (membrane) {
    uint tile = recipe_cell(c.membrane_recipe, ivec3(cell.xy, 0));
    if (kTwoLevel) return trace_atom_tile(inst, ci, tl, w.mt, w.chart, cell.xy, tile, slot_or_box, o, d);
    membrane_element_query(rc, w, tile, cell.xy, o, d, e);
  } else if (!core_element_query(c, rc, slot_or_box, cell, o, d, e)) {
    return false;
  }
  RenderLevel level = levels[e.entry];
  if (level.count == 0u) return false;
  bool found = false;
  count_work(NANO_RC_MLAS_QUERIES);
  rayQueryEXT q;
  rayQueryInitializeEXT(q, accelerationStructureEXT(level.address), kAabbOnly, 0xFF, e.ot, e.q_lo, e.dt, e.q_hi);
  while (rayQueryProceedEXT(q)) {
    count_work(NANO_RC_MLAS_CANDIDATES);
    uint p = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false));
    if (p >= level.count) continue;
    uint m = orders[level.order_first + p];
    if (!membrane && e.mask != NANO_NO_INDEX && ((mask_words[e.mask + m / 32u] >> (m % 32u)) & 1u) == 0u) {
      count_work(NANO_RC_MASK_REJECTS);
      continue;
    }
    MoleculeInstance mi = instances[e.first + m];
    if (type_hidden(mi.molecule_type)) continue;
    Affine3 placement;
    uvec2 number;
    if (!place_element_copy(inst, c, rc, membrane, tl, w, slot_or_box, e, m, mi, placement, number)) continue;
    // mLAS-level trivial reject: the copy's bounding sphere wholly clipped.
    if (kClipping && clip_removes_whole_ball(placement.translation, molecules[mi.molecule_type].aabb_min.w)) continue;
    if (kJitter) placement = jittered(placement, number);
    if (!trace_molecule(mi.molecule_type, placement, vec3(0.0), o, d, e.q_lo)) continue;
    found = true;
    best.compartment_instance = inst;
    best.element = membrane ? meshes[c.mesh].first_triangle + tl : slot_or_box;
    best.kind = membrane ? 0u : 1u;
    best.cell = membrane ? ivec4(cell.xy, 0, 0) : ivec4(cell, 0);
    best.instance = m;
    best.copy_number_lo = number.x;
    best.copy_number_hi = number.y;
    if (best_t >= e.q_lo) rayQueryGenerateIntersectionEXT(q, best_t);  // a hit must lie in the query's range
  }
  return found;
}

// Whether the medium copy centred at region-space c (medium_copy_centre) with radius r stands clear
// of every compartment instance: the instances whose exclusion box holds c (a point query of the
// exclusion structure), each by its field (shared/medium.h, as the CPU oracle decides).
bool medium_copy_kept(vec3 c, float r) {
  float clearance = medium[0].region_max.w;
  uint n = render_medium.numbers.z;
  bool kept = true;
  count_work(NANO_RC_MEDIUM_KEEP_QUERIES);
  rayQueryEXT e;
  rayQueryInitializeEXT(e, exclusion_tlas, kAabbOnly, 0xFF, c, 0.0, vec3(0.57735027), 1e-3);
  while (rayQueryProceedEXT(e)) {
    uint i = uint(rayQueryGetIntersectionPrimitiveIndexEXT(e, false));
    if (i >= n) continue;
    MediumInstance m = medium_instances[i];
    if (m.ids.x >= uint(exclusion_fields.length())) continue;
    ExclusionField f = exclusion_fields[m.ids.x];
    ivec3 cell;
    vec3 frac;
    if (!exclusion_cell(f, medium_to_compartment(m, c), cell, frac)) continue;
    float corners[8];
    for (int k = 0; k < 8; ++k) corners[k] = exclusion_values[exclusion_node(f, cell + ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1))];
    if (!medium_copy_clear(exclusion_trilinear(corners, frac), f, m.stretch.x, r, clearance)) {
      kept = false;
      rayQueryTerminateEXT(e);
    }
  }
  return kept;
}

// The medium copies of region box ijk on the ray (o, d) in eye-box space: the box's cube from the
// medium's periodic recipe, its mLAS, the copy's sphere, the keep rule, then its atoms.
bool trace_medium_box(ivec3 ijk, vec3 o, vec3 d) {
  Medium md = medium[0];
  float B = md.region_min.w;
  vec3 box_min = vec3(ijk - render_medium.eye_box.xyz) * B;
  float tn;
  float tf;
  if (!aabb_intersect(box_min + render_medium.reach_lo.xyz, box_min + render_medium.reach_hi.xyz, o, d, 0.0, best_t, tn, tf)) return false;
  if (kClipping && clip_removes_box(box_min + render_medium.reach_lo.xyz, box_min + render_medium.reach_hi.xyz)) return false;
  uint cube = recipe_cell(md.boxes.w, ijk);
  RenderLevel level = levels[frame.levels.y + cube];
  if (level.count == 0u) return false;
  uint first = cubes[cube].first_instance;
  uint box = uint(ijk.x) + md.boxes.x * (uint(ijk.y) + md.boxes.y * uint(ijk.z));
  bool found = false;
  count_work(NANO_RC_MLAS_QUERIES);
  rayQueryEXT q;
  rayQueryInitializeEXT(q, accelerationStructureEXT(level.address), kAabbOnly, 0xFF, o - box_min, 0.0, d, best_t);
  while (rayQueryProceedEXT(q)) {
    count_work(NANO_RC_MLAS_CANDIDATES);
    uint p = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false));
    if (p >= level.count) continue;
    uint m = orders[level.order_first + p];
    MoleculeInstance mi = instances[first + m];
    if (type_hidden(mi.molecule_type)) continue;
    float r = molecules[mi.molecule_type].aabb_min.w;
    // The ray must meet the copy's sphere before the keep rule's query is worth asking.
    if (!sphere_intersect(o, d, box_min + mi.position.xyz, r, tn, tf) || tf < 0.0 || tn > best_t) continue;
    if (!medium_copy_kept(medium_copy_centre(ijk, B, mi.position.xyz), r)) {
      count_work(NANO_RC_MEDIUM_REJECTS);
      continue;
    }
    Affine3 placement = core_soluble_molecule(box_min, mi.position.xyz, mi.rotation);
    uvec2 number = copy_number_core(render_medium.numbers.xy, uvec2(0u), box, md.tiles.z, m);
    if (kClipping && clip_removes_whole_ball(placement.translation, r)) continue;
    if (kJitter) placement = jittered(placement, number);
    // The oracle places medium copies exactly (region corner + box + position, in double): the
    // translation's float rounding goes back in as its low part.
    vec3 translation_hi;
    vec3 translation_lo;
    two_diff(box_min, -mi.position.xyz, translation_hi, translation_lo);
    if (!trace_molecule(mi.molecule_type, placement, translation_lo, o, d, 0.0)) continue;
    found = true;
    best.compartment_instance = NANO_MEDIUM_OWNER;
    best.element = box;
    best.kind = NANO_KIND_MEDIUM;
    best.cell = ivec4(ijk, 0);
    best.instance = m;
    best.copy_number_lo = number.x;
    best.copy_number_hi = number.y;
    rayQueryGenerateIntersectionEXT(q, best_t);
  }
  return found;
}

// The medium on the ray (origin camera-relative world, unit d) up to best_t: a 3D-DDA over the
// region's boxes widened by one (a copy reaches at most one box beyond its own), at each cell the
// boxes within one step not traced at the cell before, as the core walk does; in eye-box space.
void trace_medium(vec3 origin, vec3 d) {
  Medium md = medium[0];
  float B = md.region_min.w;
  ivec3 boxes = ivec3(md.boxes.xyz);
  ivec3 eye_box = render_medium.eye_box.xyz;
  vec3 o = render_medium.eye_hi.xyz + origin;
  eye_lo = render_medium.eye_lo.xyz;
  if (kClipping) load_clip_half_spaces(mat4x3(vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), vec3(0.0, 0.0, 1.0), -render_medium.eye_hi.xyz));
  GridDda it;
  dda_init(it, vec3(ivec3(-1) - eye_box) * B, vec3(B), boxes + ivec3(2), o, d, 0.0, best_t);
  ivec3 cell;
  float ta;
  ivec3 previous = ivec3(-1000000);
  bool found = false;
  while (dda_current(it, cell, ta)) {
    if (ta > best_t) break;
    count_work(NANO_RC_MEDIUM_STEPS);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          ivec3 ijk = cell - ivec3(1) + ivec3(dx, dy, dz);
          if (any(lessThan(ijk, ivec3(0))) || any(greaterThanEqual(ijk, boxes))) continue;
          ivec3 from_previous = abs(ijk - (previous - ivec3(1)));
          if (max(from_previous.x, max(from_previous.y, from_previous.z)) <= 1) continue;
          if (trace_medium_box(ijk, o, d)) found = true;
        }
    previous = cell;
    dda_advance(it);
  }
  if (found) best_to_world = mat4x3(vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), vec3(0.0, 0.0, 1.0), -render_medium.eye_hi.xyz);
}

// Forgets the best hit: nothing met yet up to t_max.
void reset_best(float t_max) {
  best_t = t_max;
  best.depth = placement_inf();
  best.compartment_instance = kNoHit;
  best.element = kNoHit;
  best.kind = kNoHit;
  best.cell = ivec4(-1);
  best.instance = kNoHit;
  best.atom = kNoHit;
  best.copy_number_lo = kNoHit;
  best.copy_number_hi = kNoHit;
  best_normal_c = vec3(0.0);
  best_type = 0u;
}

// Traces one ray through the whole scene: origin camera-relative world, unit direction d, hits in
// [0, t_max]. kEyeFromHost: the ray enters each instance's compartment space through the host's
// double computation (RenderInstance), not the driver's float WorldToObject: the eye as a two-float
// sum, a secondary ray's (AO, shadows) origin as the eye plus L⁻¹·origin. Leaves the hit in best*.
bool trace_scene(vec3 origin, vec3 d, float t_max, bool primary) {
  reset_best(t_max);
  bool use_flat = kFlat && frame.flat_eye.w != 0.0;
  // Two passes of one query: the flat level first (its hit bounds every µLAS candidate), then the
  // µLAS — one traversal in the compiled code, not two.
  rayQueryEXT q;
  for (bool flat_pass = use_flat;; flat_pass = false) {
  if (flat_pass) {
    // The level's space is camera-relative world moved by flat_eye: x_camera = x_level − flat_eye.
    if (kClipping) load_clip_half_spaces(mat4x3(vec3(1.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), vec3(0.0, 0.0, 1.0), -frame.flat_eye.xyz));
    count_work(NANO_RC_FLAT_QUERIES);
    rayQueryInitializeEXT(q, flat_tlas, kAabbOnly, 0xFF, origin + frame.flat_eye.xyz, 0.0, d, best_t);
  } else {
    count_work(NANO_RC_ULAS_QUERIES);
    rayQueryInitializeEXT(q, ulas, kAabbOnly, 0xFF, origin, 0.0, d, best_t);
  }
  while (rayQueryProceedEXT(q)) {
    if (rayQueryGetIntersectionTypeEXT(q, false) != gl_RayQueryCandidateIntersectionAABBEXT) continue;
    if (flat_pass) {
      if (flat_atom_hit(uint(rayQueryGetIntersectionInstanceCustomIndexEXT(q, false)),
                        uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false)),
                        rayQueryGetIntersectionObjectRayOriginEXT(q, false),
                        rayQueryGetIntersectionObjectRayDirectionEXT(q, false),
                        rayQueryGetIntersectionObjectToWorldEXT(q, false),
                        rayQueryGetIntersectionWorldToObjectEXT(q, false)))
        rayQueryGenerateIntersectionEXT(q, best_t);
      continue;
    }
    count_work(NANO_RC_ULAS_CANDIDATES);
    uint inst = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(q, false));
    uint prim = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false));
    vec3 o;
    vec3 od;
    if (kEyeFromHost) {
      RenderInstance ri = render_instances[inst];
      mat3 from_world = transpose(mat3(ri.from_world[0].xyz, ri.from_world[1].xyz, ri.from_world[2].xyz));
      od = from_world * d;
      o = primary ? ri.eye_hi.xyz : ri.eye_hi.xyz + from_world * origin;
      eye_lo = ri.eye_lo.xyz;
    } else {
      o = rayQueryGetIntersectionObjectRayOriginEXT(q, false);
      od = rayQueryGetIntersectionObjectRayDirectionEXT(q, false);
      eye_lo = vec3(0.0);
    }
    if (kClipping) load_clip_half_spaces(rayQueryGetIntersectionObjectToWorldEXT(q, false));
    uint ci = render_instances[inst].base.z;
    RenderCompartment rc = render_compartments[ci];
    Compartment c = compartments[ci];
    bool membrane = prim < rc.counts.z;
    bool found;
    if (membrane)
      found = trace_prism(inst, ci, c, rc, prim, use_flat, o, od);
    else
      found = trace_core_grid(inst, ci, c, rc, o, od);
    if (found) {
      best_to_world = rayQueryGetIntersectionObjectToWorldEXT(q, false);
      rayQueryGenerateIntersectionEXT(q, best_t);
    }
  }
  if (!flat_pass) break;
  }
  if (kMedium) trace_medium(origin, d);
  return best.atom != kNoHit;
}

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
