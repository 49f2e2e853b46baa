// Every descriptor binding, specialization-constant id and workgroup size of the compute pipelines,
// declared once for the shaders (layout qualifiers take constant expressions) and for the C++ that
// builds the descriptor sets and pipelines, so the two cannot drift apart.
#ifndef NANO_BINDINGS_H
#define NANO_BINDINGS_H

#include "glsl_cpp.h"

NANO_BEGIN

// Both pipelines dispatch square workgroups of this many invocations a side, one per pixel.
NANO_CONST uint NANO_WORKGROUP_SIZE = 8u;

// Each pipeline has one descriptor set (vk::ComputePipelineDesc::sets holds just it).
NANO_CONST uint NANO_DESCRIPTOR_SET = 0u;

// shaders/render/render.comp, set 0. Bindings below NANO_SCENE_BINDING_COUNT hold the scene (one
// package section or derived buffer each: runtime/render/levels/, one file per level); the last four the frame.
// A binding holding one package section is named after it: NANO_B_<name in format/section_table.hpp>.
NANO_CONST uint NANO_B_ULAS = 0u;  // the µLAS; every other binding is a storage buffer
NANO_CONST uint NANO_B_MOLECULES = 1u;
NANO_CONST uint NANO_B_ATOMS = 2u;
NANO_CONST uint NANO_B_TILES2D = 3u;
NANO_CONST uint NANO_B_TILES3D = 4u;
NANO_CONST uint NANO_B_INSTANCES = 5u;
NANO_CONST uint NANO_B_RECIPES = 6u;
NANO_CONST uint NANO_B_RECIPE_INDICES = 7u;
NANO_CONST uint NANO_B_MESHES = 8u;
NANO_CONST uint NANO_B_VERTEX_POSITIONS = 9u;
NANO_CONST uint NANO_B_VERTEX_NORMALS = 10u;
NANO_CONST uint NANO_B_VERTEX_UVS = 11u;
NANO_CONST uint NANO_B_TRIANGLES = 12u;
NANO_CONST uint NANO_B_TRIANGLE_SHELLS = 13u;
NANO_CONST uint NANO_B_COMPARTMENTS = 14u;
NANO_CONST uint NANO_B_OCCUPANCY = 15u;
NANO_CONST uint NANO_B_BOUNDARY_BOXES = 16u;
NANO_CONST uint NANO_B_MASK_WORDS = 17u;
NANO_CONST uint NANO_B_RENDER_COMPARTMENTS = 18u;
NANO_CONST uint NANO_B_RENDER_INSTANCES = 19u;
NANO_CONST uint NANO_B_LEVELS = 20u;
NANO_CONST uint NANO_B_ORDERS = 21u;
NANO_CONST uint NANO_B_TRIANGLE_DROPS = 22u;
NANO_CONST uint NANO_B_DROPPED_COPIES = 23u;
NANO_CONST uint NANO_B_BEADS = 24u;  // coarse beads per molecule type (render_scene.h Bead; the level of detail)
NANO_CONST uint NANO_B_FLAT_TLAS = 25u;    // the flat level (render_scene.h FlatCopy); the µLAS stands in when empty
NANO_CONST uint NANO_B_FLAT_COPIES = 26u;
NANO_CONST uint NANO_B_FLAT_TRIANGLES = 27u;  // one bit per triangle of every compartment instance: flattened
NANO_CONST uint NANO_B_CORE_SKIP = 28u;  // the core grids' skip levels (shared/core_skip.h), 8 cells a word
NANO_CONST uint NANO_B_KEPT_BOXES = 29u;  // per BOUNDARY box record: what its keep-mask keeps (render_scene.h kept_box_unpack)
NANO_CONST uint NANO_B_MEDIUM = 30u;             // the medium (shared/medium.h), a zero record when the package has none
NANO_CONST uint NANO_B_EXCLUSION_FIELDS = 31u;
NANO_CONST uint NANO_B_EXCLUSION_VALUES = 32u;
NANO_CONST uint NANO_B_MEDIUM_INSTANCES = 33u;   // per compartment instance: region → compartment space
NANO_CONST uint NANO_B_RENDER_MEDIUM = 34u;      // per frame: the eye in region space, copy numbers
NANO_CONST uint NANO_B_EXCLUSION_TLAS = 35u;     // the instances' exclusion fields as boxes in region space
NANO_CONST uint NANO_SCENE_BINDING_COUNT = 36u;
NANO_CONST uint NANO_B_FRAME = 36u;
NANO_CONST uint NANO_B_HITS = 37u;
NANO_CONST uint NANO_B_COLOURS = 38u;
NANO_CONST uint NANO_B_COUNTERS = 39u;  // per pixel work counters (shared/ray_counters.h); a one-word buffer when off
NANO_CONST uint NANO_RENDER_BINDING_COUNT = 40u;

// render.comp's specialization constants (runtime/render/renderer.cpp sets them per variant).
NANO_CONST int NANO_SPEC_EXACT_PRISM = 0;
NANO_CONST int NANO_SPEC_REPLICATION_LAS = 1;
NANO_CONST int NANO_SPEC_TWO_LEVEL = 2;
NANO_CONST int NANO_SPEC_CLIPPING = 3;
NANO_CONST int NANO_SPEC_JITTER = 4;
NANO_CONST int NANO_SPEC_AMBIENT_OCCLUSION = 5;
NANO_CONST int NANO_SPEC_SHADOWS = 6;
NANO_CONST int NANO_SPEC_EYE_FROM_HOST = 7;
NANO_CONST int NANO_SPEC_WORLD_SPACE_ULAS = 8;
NANO_CONST int NANO_SPEC_COUNTERS = 9;
NANO_CONST int NANO_SPEC_LOD = 10;
NANO_CONST int NANO_SPEC_FLAT = 11;  // the flat level is traced (runtime/render/flat_level.hpp)
NANO_CONST int NANO_SPEC_OUTLINES = 12;
// Some replication area has more than NANO_DIRECT_SLOTS slots (GpuScene::has_large_replication_areas).
NANO_CONST int NANO_SPEC_LARGE_REPLICATION_AREAS = 13;
// The package has a medium and it is shown (GpuScene::has_medium, RenderSettings::show_medium).
NANO_CONST int NANO_SPEC_MEDIUM = 14;
// Some molecule type is hidden (--hide; its levels have count 0): candidates of a hidden type are
// dropped before their placement, ownership or keep query is computed.
NANO_CONST int NANO_SPEC_HIDDEN_TYPES = 15;
// Fog (depth cueing over the frame's depth range, in the image pass).
NANO_CONST int NANO_SPEC_FOG = 16;

// shaders/explicit_instancing/instanced.comp, set 0 (explicit instancing: runtime/explicit_instancing/).
NANO_CONST uint NANO_IB_TLAS = 0u;  // one instance per copy; every other binding is a storage buffer
NANO_CONST uint NANO_IB_COPIES = 1u;
NANO_CONST uint NANO_IB_TYPES = 2u;
NANO_CONST uint NANO_IB_ATOMS = 3u;
NANO_CONST uint NANO_IB_ORDERS = 4u;
NANO_CONST uint NANO_INSTANCED_SCENE_BINDING_COUNT = 5u;
NANO_CONST uint NANO_IB_FRAME = 5u;
NANO_CONST uint NANO_IB_HITS = 6u;
NANO_CONST uint NANO_IB_COLOURS = 7u;
NANO_CONST uint NANO_IB_COUNTERS = 8u;  // as NANO_B_COUNTERS
NANO_CONST uint NANO_INSTANCED_BINDING_COUNT = 9u;

// instanced.comp's specialization constant.
NANO_CONST int NANO_SPEC_INSTANCED_COUNTERS = 0;

NANO_STATIC_ASSERT(NANO_DESCRIPTOR_SET == 0u, "a pipeline's first and only set is set 0");
NANO_STATIC_ASSERT(NANO_B_EXCLUSION_TLAS + 1u == NANO_SCENE_BINDING_COUNT, "scene bindings are 0 .. count - 1");
NANO_STATIC_ASSERT(NANO_B_COUNTERS + 1u == NANO_RENDER_BINDING_COUNT, "frame bindings follow the scene's");
NANO_STATIC_ASSERT(NANO_IB_ORDERS + 1u == NANO_INSTANCED_SCENE_BINDING_COUNT, "instanced scene bindings are 0 .. count - 1");
NANO_STATIC_ASSERT(NANO_IB_COUNTERS + 1u == NANO_INSTANCED_BINDING_COUNT, "instanced frame bindings follow the scene's");

NANO_END

#endif
