// Records of the .nup package that shaders read in place (std430) and C++ reads from the memory map.
// One definition serves both: every vec4/uvec4 member sits at a multiple of 16 bytes and every struct
// holding one is a multiple of 16 bytes long, so std430's offsets and array strides equal the C++
// layout (GLM's vec4 is 16 bytes with 4-byte alignment). The C++ static_asserts at the end pin it.
// Reserved members must be zero: a later minor version may give them a meaning. The byte layout of
// every section is documented in docs/format.md.
#ifndef NANO_PACKAGE_RECORDS_H
#define NANO_PACKAGE_RECORDS_H

#include "glsl_cpp.h"

NANO_BEGIN

// "No such record" in an optional index (a compartment without membrane, for instance).
NANO_CONST uint NANO_NO_INDEX = 0xFFFFFFFFu;

// Box occupancy values (one byte per core-grid box).
NANO_CONST uint NANO_BOX_OUTSIDE = 0u;
NANO_CONST uint NANO_BOX_INSIDE = 1u;
NANO_CONST uint NANO_BOX_BOUNDARY = 2u;

// Recipe dimensionality.
NANO_CONST uint NANO_RECIPE_2D = 2u;
NANO_CONST uint NANO_RECIPE_3D = 3u;

// Section "molecules": one record per molecule type, in molecule (object) space, Å.
struct MoleculeType {
  vec4 aabb_min;     // xyz: AABB minimum over atom spheres; w: bounding radius about the origin
  vec4 aabb_max;     // xyz: AABB maximum; w: reserved
  vec4 up_axis;      // xyz: unit axis that membrane placement aligns with the surface normal; w: reserved
  vec4 colour;       // linear RGBA in [0, 1]
  uint first_atom;   // range in section "atoms"
  uint atom_count;
  uint name_offset;  // name: bytes [offset, offset+length) of section "strings"
  uint name_length;
  uint source_offset;  // source id (PDB/mmCIF id or file name) in section "strings"
  uint source_length;
  uint reserved0;
  uint reserved1;
};

// Section "atoms": object-space centre (xyz, Å) and radius (w, Å), float32, no quantisation.
struct Atom {
  vec4 centre_radius;
};

// Section "tiles2d": Wang squares of the membrane shells.
struct Tile2D {
  uvec4 edge_colours;  // N, E, S, W
  vec4 size;           // x, y: tile extent in tile space (Å); z: shell thickness (Å); w: reserved
  uint first_instance; // range in section "instances", positions in this tile's space
  uint instance_count;
  uint reserved0;
  uint reserved1;
};

// Section "tiles3d": Wang cubes of the core grids.
struct Tile3D {
  uvec4 face_colours_xy;  // -x, +x, -y, +y
  uvec4 face_colours_z;   // x: -z, y: +z, zw: reserved
  vec4 size;              // xyz: cube extent in tile space (Å); w: reserved
  uint first_instance;    // range in section "instances"
  uint instance_count;
  uint reserved0;
  uint reserved1;
};

// Section "instances": a molecule placed in a tile's space.
struct MoleculeInstance {
  vec4 rotation;   // unit quaternion (x, y, z, w), molecule space -> tile space
  vec4 position;   // xyz: molecule origin in tile space; w: reserved
  vec4 aabb_min;   // xyz: tile-space AABB of the placed molecule; w: reserved
  vec4 aabb_max;
  uint molecule_type;  // index into section "molecules"
  uint flags;          // NANO_INSTANCE_* bits; the others zero
  uint reserved1;
  uint reserved2;
};

// MoleculeInstance.flags: an alternate of a membrane square stands in for a neighbour copy the
// surface may push into a clash (the base lipid of a place given to another species): it is shown
// only by the triangles that list its key in "dropped_copies", the others showing the copy it
// stands in for. Every other instance is shown unless listed.
NANO_CONST uint NANO_INSTANCE_ALTERNATE = 1u;

// Section "recipes": a 2D or 3D array of tile indices, x fastest, stored in "recipe_indices".
struct Recipe {
  uvec4 dims;        // xyz: tiles per axis (z = 1 for 2D); w: NANO_RECIPE_2D or NANO_RECIPE_3D
  uint first_index;  // range in section "recipe_indices"; index_count = dims.x * dims.y * dims.z
  uint index_count;
  uint reserved0;
  uint reserved1;
};

// Section "meshes": proxy geometry ranges. Triangle vertex indices are local to the mesh's range.
struct Mesh {
  vec4 aabb_min;  // xyz: mesh-space AABB; w: reserved
  vec4 aabb_max;
  uint first_vertex;  // range in "vertex_positions" / "vertex_normals" / "vertex_uvs"
  uint vertex_count;
  uint first_triangle;  // range in "triangles" and "triangle_shells"
  uint triangle_count;
};

// Section "vertex_positions" (xyz, w reserved) and "vertex_normals" (unit xyz, w reserved): vec4.
// Section "vertex_uvs": vec2.

// Section "triangles": three vertex indices, tightly packed so it doubles as a Vulkan index buffer.
struct Triangle {
  uint v0;
  uint v1;
  uint v2;
};

// Section "triangle_shells": the prism built over each triangle, parallel to "triangles".
struct TriangleShell {
  vec4 uv_min_max;    // u_min, v_min, u_max, v_max of the triangle's UV box
  float h_plus;       // shell extent above the surface along vertex normals (Å, >= 0)
  float h_minus;      // extent below (Å, >= 0)
  float side_offset;  // outward offset of the side walls (Å, >= 0)
  uint seam_edges;    // UV-seam rule (shared/seam.h): bit k (0-2) edge k (corners k, k+1 mod 3) is a
                      // seam this triangle yields on; bit 3+k corner k touches a seam its chart
                      // yields on. Molecules near them are dropped. Only bits 0-5
};

// Section "triangle_drops" (format 2.2, optional; parallel to "triangles" when present): the
// membrane copies a triangle owns that the baker removed because, placed on the real surface, they
// would clash with a kept copy (or stand where a compartment-level protein replaced them), and the
// alternates (NANO_INSTANCE_ALTERNATE) it shows in their place. Keys of
// section "dropped_copies" [first, +count), strictly ascending:
// membrane_copy_key(slot, instance) = slot · 2^16 + instance, slot = sx + W·sy in the replication
// area (W = the compartment's replication_width), instance < 2^16 within the slot's Wang square.
NANO_CONST uint NANO_DROP_INSTANCE_BITS = 16u;
struct TriangleDrops {
  uint first;  // range in section "dropped_copies"
  uint count;
};

// Section "dropped_copies": uint keys, see TriangleDrops.

// Section "compartments": a mesh with its membrane shell and its soluble core grid.
struct Compartment {
  vec4 grid_min;   // xyz: core-grid AABB minimum (mesh space); w: box edge length (Å)
  uvec4 grid_dims; // xyz: boxes per axis; w: first byte of this grid in section "occupancy"
  vec4 scales;     // x: UV scale k (Å of surface per UV unit); y: Wang square size (Å);
                   // z: Wang cube size (Å); w: reserved, 0 (format 1 kept the one-sided seam
                   // rule's radius there; format 2's seam bits are two-sided, shared/seam.h)
  uint mesh;               // index into "meshes"
  uint membrane_first_tile;  // tile set: range in "tiles2d"
  uint membrane_tile_count;
  uint membrane_recipe;      // index into "recipes" (2D), or NANO_NO_INDEX for no membrane
  uint soluble_first_tile;   // cube set: range in "tiles3d"
  uint soluble_tile_count;
  uint soluble_recipe;       // index into "recipes" (3D), or NANO_NO_INDEX for no core grid
  uint replication_width;    // replication area W x H, in tiles
  uint replication_height;
  uint name_offset;          // name in section "strings"
  uint name_length;
  uint reserved0;
  uvec4 core_masks;          // keep-masks of the core grid's BOUNDARY boxes: x: first record in
                             // "boundary_boxes", y: count (0 without a core grid); zw: reserved
};

// Section "boundary_boxes": one record per BOUNDARY box of a core grid, ascending `box` within each
// compartment's range, so a shader finds a box's mask by binary search. Every box of one compartment
// has the same number of mask words, W = ceil(largest instance_count of its cube set / 32), and
// consecutive records' first_word differ by exactly W: whichever cube the recipe puts in the box, a
// shader reads mask_words[first_word + m / 32] for its molecule m without reading the cube first.
struct BoundaryBox {
  uint box;         // linear index in the compartment's core grid, i + X * (j + Y * k)
  uint first_word;  // the box's W words in section "mask_words"; bit m % 32 of word m / 32 = keep
                    // molecule m (the m-th instance of the box's cube)
};

// Section "mask_words": uint array, the keep-mask words of all boundary boxes.

// Section "scene": exactly one record.
struct SceneSettings {
  vec4 camera_position;  // xyz: default camera position (world, Å); w: vertical field of view (radians)
  vec4 camera_look_at;   // xyz: the point looked at; w: reserved
  vec4 camera_up;      // xyz: up direction; w: reserved
  uint effect_flags;   // one bit per effect, EffectDeclaration::package_flag (common/effect_table.hpp); unknown bits are ignored
  uint reserved0;
  uint reserved1;
  uint reserved2;
};

// Section "effects" (format 2.1, optional): exactly one record with the parameters of the effects
// SceneSettings.effect_flags turns on. Members of an effect that is off are zero. Without this
// section every effect is off, whatever the flags say (2.0 packages).
NANO_CONST uint NANO_MAX_CLIP_PLANES = 8u;
struct SceneEffects {
  vec4 clip_planes[8];     // (unit n, d), world Å: points with n·p + d ≥ 0 stay; the first clip_plane_count
  vec4 clip_box_min;       // xyz: world minimum; w: 1 = the box clips, 0 = no box
  vec4 clip_box_max;       // xyz: world maximum; w: reserved
  vec4 spin;               // steady proxy motion (no keyframes): xyz unit axis, w degrees per second
  vec4 velocity;           // xyz: Å per second; w: reserved
  vec2 jitter;             // x: amplitude (degrees), y: frequency (Hz)
  vec2 fog_range;          // x: start, y: span, as fractions of the frame's depth range (format ≤ 2.8: reserved zeros)
  vec2 ambient_occlusion;  // x: rays per pixel, y: radius (Å)
  float ao_radius_pixels;  // the radius at least this many pixels at the hit (format ≤ 2.8: reserved zero)
  float fog_strength;      // in [0, 1] (format ≤ 2.8: reserved zero)
  vec3 shadow_light;       // unit direction towards the light (world)
  float outline_fade_pixels;   // a copy's contours are full from this radius on screen (format ≤ 2.8: reserved zero)
  uint clip_plane_count;   // ≤ NANO_MAX_CLIP_PLANES
  float outline_width_pixels;  // format 2.1 readers saw these three as reserved zeros; outlines off keeps them zero
  float outline_crease_depth;  // Å
  uint outline_colour;         // RGBA8 as the image shows it (sRGB), R in the low byte, alpha 255
};

// Section "keyframes" (format 2.1, optional): keyframed proxy motion, ascending by (instance, time).
// Between two keys of an instance its transform is interpolated; before the first and after the
// last it holds; instances without keys keep their transform.
struct InstanceKeyframe {
  vec4 transform[3];  // rows of the 3x4 compartment → world transform at `time`
  float time;         // seconds
  uint instance;      // index into "compartment_instances"
  uint reserved0;
  uint reserved1;
};

// Section "compartment_instances": where each compartment is placed in the world.
struct CompartmentInstance {
  vec4 transform[3];  // rows of a 3x4 row-major affine transform, compartment space -> world
  uint compartment;   // index into "compartments"
  uint reserved0;
  uint reserved1;
  uint reserved2;
};

// Section "beads" (format 2.5, optional): the level of detail's coarse model of each molecule type,
// baked by bake/structure/coarse_beads.hpp: a residue, or a fragment of a large residue, as one
// sphere holding its atoms' spheres. A copy whose atoms would span under the --lod threshold is drawn
// as its type's beads. Without the section the runtime has no level of detail.
struct Bead {
  vec4 centre_radius;  // molecule space, Å; radius > 0
  uint atom;           // the atom a hit on the bead reports (index into "atoms", inside the type's
                       // range): the bead's atom nearest its centre
  uint atom_count;     // atoms merged into the bead (≥ 1)
  uint reserved0;
  uint reserved1;
};

// Section "bead_ranges" (format 2.5, with "beads"): parallel to "molecules", each type's beads.
struct BeadRange {
  uint first;  // range in section "beads", count ≥ 1
  uint count;
};

NANO_END

#ifdef __cplusplus
#include <cstddef>
// std430 offsets and strides, pinned for C++ so a member added in the wrong place fails to compile.
#define NANO_PIN(T, size) static_assert(sizeof(nano::gpu::T) == (size), #T " size");
#define NANO_AT(T, m, off) static_assert(offsetof(nano::gpu::T, m) == (off), #T "." #m " offset");
NANO_PIN(SceneEffects, 256)
NANO_AT(SceneEffects, clip_box_min, 128) NANO_AT(SceneEffects, jitter, 192) NANO_AT(SceneEffects, fog_range, 200)
NANO_AT(SceneEffects, ambient_occlusion, 208) NANO_AT(SceneEffects, fog_strength, 220) NANO_AT(SceneEffects, shadow_light, 224)
NANO_AT(SceneEffects, outline_fade_pixels, 236)
NANO_AT(SceneEffects, clip_plane_count, 240) NANO_AT(SceneEffects, outline_width_pixels, 244)
NANO_AT(SceneEffects, outline_crease_depth, 248) NANO_AT(SceneEffects, outline_colour, 252)
NANO_PIN(InstanceKeyframe, 64)
NANO_AT(InstanceKeyframe, time, 48) NANO_AT(InstanceKeyframe, instance, 52)
NANO_PIN(MoleculeType, 96)
NANO_AT(MoleculeType, aabb_min, 0) NANO_AT(MoleculeType, aabb_max, 16) NANO_AT(MoleculeType, up_axis, 32)
NANO_AT(MoleculeType, colour, 48) NANO_AT(MoleculeType, first_atom, 64) NANO_AT(MoleculeType, atom_count, 68)
NANO_AT(MoleculeType, name_offset, 72) NANO_AT(MoleculeType, name_length, 76)
NANO_AT(MoleculeType, source_offset, 80) NANO_AT(MoleculeType, source_length, 84)
NANO_AT(MoleculeType, reserved0, 88) NANO_AT(MoleculeType, reserved1, 92)
NANO_PIN(Atom, 16)
NANO_AT(Atom, centre_radius, 0)
NANO_PIN(Tile2D, 48)
NANO_AT(Tile2D, edge_colours, 0) NANO_AT(Tile2D, size, 16) NANO_AT(Tile2D, first_instance, 32)
NANO_AT(Tile2D, instance_count, 36) NANO_AT(Tile2D, reserved0, 40) NANO_AT(Tile2D, reserved1, 44)
NANO_PIN(Tile3D, 64)
NANO_AT(Tile3D, face_colours_xy, 0) NANO_AT(Tile3D, face_colours_z, 16) NANO_AT(Tile3D, size, 32)
NANO_AT(Tile3D, first_instance, 48) NANO_AT(Tile3D, instance_count, 52) NANO_AT(Tile3D, reserved0, 56)
NANO_AT(Tile3D, reserved1, 60)
NANO_PIN(MoleculeInstance, 80)
NANO_AT(MoleculeInstance, rotation, 0) NANO_AT(MoleculeInstance, position, 16)
NANO_AT(MoleculeInstance, aabb_min, 32) NANO_AT(MoleculeInstance, aabb_max, 48)
NANO_AT(MoleculeInstance, molecule_type, 64) NANO_AT(MoleculeInstance, flags, 68)
NANO_AT(MoleculeInstance, reserved1, 72) NANO_AT(MoleculeInstance, reserved2, 76)
NANO_PIN(Recipe, 32)
NANO_AT(Recipe, dims, 0) NANO_AT(Recipe, first_index, 16) NANO_AT(Recipe, index_count, 20)
NANO_AT(Recipe, reserved0, 24) NANO_AT(Recipe, reserved1, 28)
NANO_PIN(Mesh, 48)
NANO_AT(Mesh, aabb_min, 0) NANO_AT(Mesh, aabb_max, 16) NANO_AT(Mesh, first_vertex, 32)
NANO_AT(Mesh, vertex_count, 36) NANO_AT(Mesh, first_triangle, 40) NANO_AT(Mesh, triangle_count, 44)
NANO_PIN(Triangle, 12)
NANO_AT(Triangle, v0, 0) NANO_AT(Triangle, v1, 4) NANO_AT(Triangle, v2, 8)
NANO_PIN(TriangleShell, 32)
NANO_AT(TriangleShell, uv_min_max, 0) NANO_AT(TriangleShell, h_plus, 16) NANO_AT(TriangleShell, h_minus, 20)
NANO_AT(TriangleShell, side_offset, 24) NANO_AT(TriangleShell, seam_edges, 28)
NANO_PIN(Compartment, 112)
NANO_AT(Compartment, grid_min, 0) NANO_AT(Compartment, grid_dims, 16) NANO_AT(Compartment, scales, 32)
NANO_AT(Compartment, mesh, 48) NANO_AT(Compartment, membrane_first_tile, 52)
NANO_AT(Compartment, membrane_tile_count, 56) NANO_AT(Compartment, membrane_recipe, 60)
NANO_AT(Compartment, soluble_first_tile, 64) NANO_AT(Compartment, soluble_tile_count, 68)
NANO_AT(Compartment, soluble_recipe, 72) NANO_AT(Compartment, replication_width, 76)
NANO_AT(Compartment, replication_height, 80) NANO_AT(Compartment, name_offset, 84)
NANO_AT(Compartment, name_length, 88) NANO_AT(Compartment, reserved0, 92) NANO_AT(Compartment, core_masks, 96)
NANO_PIN(TriangleDrops, 8)
NANO_AT(TriangleDrops, first, 0) NANO_AT(TriangleDrops, count, 4)
NANO_PIN(Bead, 32)
NANO_AT(Bead, centre_radius, 0) NANO_AT(Bead, atom, 16) NANO_AT(Bead, atom_count, 20)
NANO_AT(Bead, reserved0, 24) NANO_AT(Bead, reserved1, 28)
NANO_PIN(BeadRange, 8)
NANO_AT(BeadRange, first, 0) NANO_AT(BeadRange, count, 4)
NANO_PIN(BoundaryBox, 8)
NANO_AT(BoundaryBox, box, 0) NANO_AT(BoundaryBox, first_word, 4)
NANO_PIN(SceneSettings, 64)
NANO_AT(SceneSettings, camera_position, 0) NANO_AT(SceneSettings, camera_look_at, 16)
NANO_AT(SceneSettings, camera_up, 32) NANO_AT(SceneSettings, effect_flags, 48)
NANO_AT(SceneSettings, reserved0, 52) NANO_AT(SceneSettings, reserved1, 56) NANO_AT(SceneSettings, reserved2, 60)
NANO_PIN(CompartmentInstance, 64)
NANO_AT(CompartmentInstance, transform, 0) NANO_AT(CompartmentInstance, compartment, 48)
NANO_AT(CompartmentInstance, reserved0, 52) NANO_AT(CompartmentInstance, reserved1, 56)
NANO_AT(CompartmentInstance, reserved2, 60)
static_assert(sizeof(glm::vec4) == 16 && sizeof(glm::uvec4) == 16 && sizeof(glm::vec2) == 8, "GLM vector sizes");
#undef NANO_PIN
#undef NANO_AT
#endif

#endif
