// Packages that are structurally sound but whose contents break a semantic rule: each is
// rejected with the right rule, naming the right section and the byte of the broken member.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include "common/effect_table.hpp"
#include "tests/format/package_bytes.hpp"
#include "tests/format/sample_scene.hpp"

namespace nano::format::test {
namespace {

struct Case {
  const char* name;
  std::function<void(SampleScene&)> corrupt;
  Rule rule;
  SectionKind section;
  std::uint64_t record_offset;  // byte of the broken member within the uncompressed section
};

const float kNaN = std::numeric_limits<float>::quiet_NaN();
using glm::vec4;

// The sample's only cube grows from 1 to 33 molecules (copies of its instance), so the keep-masks
// need two words per box instead of one.
void grow_cube_past_one_word(SampleScene& s) {
  for (int i = 0; i < 32; ++i) s.instances.push_back(s.instances[3]);
  s.tiles3d[0].instance_count = 33;
  s.medium[0].tiles.z = 33;  // the medium shares the cube
}

// The grown cube with masks rewritten to match: box 199 keeps all 33 molecules, box 260 none.
void two_words_per_box(SampleScene& s) {
  grow_cube_past_one_word(s);
  s.boundary_boxes = {{199, 0}, {260, 2}};
  s.mask_words = {0xffffffffu, 1, 0, 0};
}

const Case kCases[] = {
    {"atom range past the atoms", [](SampleScene& s) { s.molecules[1].atom_count = 3; }, Rule::index_out_of_range,
     SectionKind::molecules, 96 + 64},
    {"atom range start overflow", [](SampleScene& s) { s.molecules[0].first_atom = 0xffffffffu; },
     Rule::index_out_of_range, SectionKind::molecules, 64},
    {"molecule without atoms", [](SampleScene& s) { s.molecules[0].atom_count = 0; }, Rule::bad_value,
     SectionKind::molecules, 68},
    {"inverted molecule AABB", [](SampleScene& s) { s.molecules[1].aabb_min.y = 5; }, Rule::inverted_aabb,
     SectionKind::molecules, 96 + 4},
    {"name outside the string table", [](SampleScene& s) { s.molecules[0].name_length = 100; },
     Rule::index_out_of_range, SectionKind::molecules, 72},
    {"NaN atom", [](SampleScene& s) { s.atoms[2].centre_radius.z = kNaN; }, Rule::non_finite, SectionKind::atoms,
     2 * 16 + 8},
    {"infinite atom radius", [](SampleScene& s) { s.atoms[4].centre_radius.w = INFINITY; }, Rule::non_finite,
     SectionKind::atoms, 4 * 16 + 12},
    {"zero atom radius", [](SampleScene& s) { s.atoms[0].centre_radius.w = 0; }, Rule::bad_value, SectionKind::atoms, 12},
    {"atom info count", [](SampleScene& s) { s.atom_info.pop_back(); }, Rule::record_size, SectionKind::atom_info, 0},
    {"control character in atom name", [](SampleScene& s) { s.atom_info[1].atom_name[0] = '\n'; }, Rule::bad_value,
     SectionKind::atom_info, 24 + 12},
    {"instance molecule type", [](SampleScene& s) { s.instances[2].molecule_type = 2; }, Rule::index_out_of_range,
     SectionKind::instances, 2 * 80 + 64},
    {"non-unit quaternion", [](SampleScene& s) { s.instances[0].rotation = glm::vec4(0, 0, 0, 2); }, Rule::bad_value,
     SectionKind::instances, 0},
    {"NaN instance position", [](SampleScene& s) { s.instances[1].position.x = kNaN; }, Rule::non_finite,
     SectionKind::instances, 80 + 16},
    {"reserved instance member", [](SampleScene& s) { s.instances[3].reserved1 = 1; }, Rule::nonzero_reserved,
     SectionKind::instances, 3 * 80 + 72},
    {"unknown instance flag", [](SampleScene& s) { s.instances[1].flags = 2; }, Rule::bad_value, SectionKind::instances,
     80 + 68},
    {"alternate in a Wang cube", [](SampleScene& s) { s.instances[3].flags = gpu::NANO_INSTANCE_ALTERNATE; },
     Rule::bad_value, SectionKind::tiles3d, 48},
    {"tile instance range", [](SampleScene& s) { s.tiles2d[1].instance_count = 3; }, Rule::index_out_of_range,
     SectionKind::tiles2d, 48 + 32},
    {"negative tile size", [](SampleScene& s) { s.tiles3d[0].size.z = -1; }, Rule::bad_value, SectionKind::tiles3d, 32 + 8},
    {"recipe tile index", [](SampleScene& s) { s.recipe_indices[2] = 2; }, Rule::index_out_of_range,
     SectionKind::recipe_indices, 2 * 4},
    {"3D recipe tile index", [](SampleScene& s) { s.recipe_indices[5] = 1; }, Rule::index_out_of_range,
     SectionKind::recipe_indices, 5 * 4},
    {"recipe dims vs count", [](SampleScene& s) { s.recipes[0].dims.x = 3; }, Rule::record_size, SectionKind::recipes, 20},
    {"recipe dims overflow", [](SampleScene& s) { s.recipes[1].dims = glm::uvec4(0x10000, 0x10000, 2, 3); },
     Rule::record_size, SectionKind::recipes, 32 + 20},
    {"recipe past the index array", [](SampleScene& s) { s.recipes[1].first_index = 5; }, Rule::index_out_of_range,
     SectionKind::recipes, 32 + 16},
    {"recipe dimensionality", [](SampleScene& s) { s.recipes[0].dims.w = 4; }, Rule::bad_value, SectionKind::recipes, 12},
    {"mesh triangle range", [](SampleScene& s) { s.meshes[0].triangle_count = 5; }, Rule::index_out_of_range,
     SectionKind::meshes, 40},
    {"mesh vertex range", [](SampleScene& s) { s.meshes[0].first_vertex = 1; }, Rule::index_out_of_range,
     SectionKind::meshes, 32},
    {"triangle vertex index", [](SampleScene& s) { s.triangles[3].v2 = 4; }, Rule::index_out_of_range,
     SectionKind::triangles, 3 * 12 + 8},
    {"NaN vertex", [](SampleScene& s) { s.vertex_positions[1].y = kNaN; }, Rule::non_finite, SectionKind::vertex_positions,
     16 + 4},
    {"NaN UV", [](SampleScene& s) { s.vertex_uvs[3].x = kNaN; }, Rule::non_finite, SectionKind::vertex_uvs, 3 * 8},
    {"normal count", [](SampleScene& s) { s.vertex_normals.pop_back(); }, Rule::record_size, SectionKind::vertex_normals, 0},
    {"inverted UV box", [](SampleScene& s) { s.triangle_shells[2].uv_min_max.x = 2; }, Rule::inverted_aabb,
     SectionKind::triangle_shells, 2 * 32},
    {"negative shell", [](SampleScene& s) { s.triangle_shells[0].h_minus = -1; }, Rule::bad_value,
     SectionKind::triangle_shells, 16},
    {"seam bit beyond 5", [](SampleScene& s) { s.triangle_shells[1].seam_edges = 64; }, Rule::bad_value,
     SectionKind::triangle_shells, 32 + 28},
    {"high seam bit", [](SampleScene& s) { s.triangle_shells[3].seam_edges = 0x80000007u; }, Rule::bad_value,
     SectionKind::triangle_shells, 3 * 32 + 28},
    {"reserved scales.w negative", [](SampleScene& s) { s.compartments[0].scales.w = -1; }, Rule::bad_value,
     SectionKind::compartments, 44},
    // Format 1 stored the set's largest bounding radius (2.5 here) in scales.w; format 2 reserves it.
    {"reserved scales.w holding a format-1 seam radius", [](SampleScene& s) { s.compartments[0].scales.w = 2.5f; },
     Rule::bad_value, SectionKind::compartments, 44},
    {"reserved scales.w without a membrane",
     [](SampleScene& s) {
       s.compartments[0].membrane_recipe = gpu::NANO_NO_INDEX;
       s.compartments[0].scales.w = 2.5f;
     },
     Rule::bad_value, SectionKind::compartments, 44},
    {"compartment mesh index", [](SampleScene& s) { s.compartments[0].mesh = 1; }, Rule::index_out_of_range,
     SectionKind::compartments, 48},
    {"compartment recipe index", [](SampleScene& s) { s.compartments[0].soluble_recipe = 2; }, Rule::index_out_of_range,
     SectionKind::compartments, 72},
    {"membrane recipe is 3D", [](SampleScene& s) { s.compartments[0].membrane_recipe = 1; }, Rule::bad_value,
     SectionKind::compartments, 52},
    {"recipe outside the tile set", [](SampleScene& s) { s.compartments[0].membrane_tile_count = 1; },
     Rule::index_out_of_range, SectionKind::compartments, 52},
    {"occupancy range", [](SampleScene& s) { s.compartments[0].grid_dims.w = 1; }, Rule::index_out_of_range,
     SectionKind::compartments, 28},
    {"zero box size", [](SampleScene& s) { s.compartments[0].grid_min.w = 0; }, Rule::bad_value, SectionKind::compartments, 12},
    {"occupancy value", [](SampleScene& s) { s.occupancy[300] = 3; }, Rule::bad_value, SectionKind::occupancy, 300},
    {"boundary-box range past the section", [](SampleScene& s) { s.compartments[0].core_masks.y = 3; },
     Rule::index_out_of_range, SectionKind::compartments, 96},
    {"boundary-box range start overflow", [](SampleScene& s) { s.compartments[0].core_masks.x = 0xffffffffu; },
     Rule::index_out_of_range, SectionKind::compartments, 96},
    {"boundary boxes without a core grid", [](SampleScene& s) { s.compartments[0].soluble_recipe = gpu::NANO_NO_INDEX; },
     Rule::bad_value, SectionKind::compartments, 100},
    {"reserved core-mask member", [](SampleScene& s) { s.compartments[0].core_masks.w = 1; }, Rule::nonzero_reserved,
     SectionKind::compartments, 108},
    {"boundary box outside the grid", [](SampleScene& s) { s.boundary_boxes[1].box = 512; }, Rule::index_out_of_range,
     SectionKind::boundary_boxes, 8},
    {"boundary boxes not ascending",
     [](SampleScene& s) { std::swap(s.boundary_boxes[0].box, s.boundary_boxes[1].box); }, Rule::bad_value,
     SectionKind::boundary_boxes, 8},
    {"listed box is inside", [](SampleScene& s) { s.boundary_boxes[1].box = 230; }, Rule::bad_value,
     SectionKind::boundary_boxes, 8},
    {"listed box is outside", [](SampleScene& s) { s.boundary_boxes[0].box = 10; }, Rule::bad_value,
     SectionKind::boundary_boxes, 0},
    {"boundary box not listed", [](SampleScene& s) { s.occupancy[300] = gpu::NANO_BOX_BOUNDARY; }, Rule::bad_value,
     SectionKind::occupancy, 300},
    {"boundary-box list cut short", [](SampleScene& s) { s.compartments[0].core_masks.y = 1; }, Rule::bad_value,
     SectionKind::occupancy, 260},
    {"mask words past the section", [](SampleScene& s) { s.mask_words.pop_back(); }, Rule::index_out_of_range,
     SectionKind::boundary_boxes, 8 + 4},
    {"first mask word overflow", [](SampleScene& s) { s.boundary_boxes[0].first_word = 0xffffffffu; },
     Rule::index_out_of_range, SectionKind::boundary_boxes, 4},
    {"masks sharing words", [](SampleScene& s) { s.boundary_boxes[1].first_word = 0; }, Rule::bad_value,
     SectionKind::boundary_boxes, 8 + 4},
    {"keep bit beyond the largest cube", [](SampleScene& s) { s.mask_words[1] = 2; }, Rule::bad_value,
     SectionKind::mask_words, 4},
    {"cube past 32 molecules with one-word masks", grow_cube_past_one_word, Rule::bad_value, SectionKind::boundary_boxes,
     8 + 4},
    {"keep bit beyond a 33-molecule cube",
     [](SampleScene& s) {
       two_words_per_box(s);
       s.mask_words[3] = 2;
     },
     Rule::bad_value, SectionKind::mask_words, 3 * 4},
    {"core skip level too high: a block that hides a copy",
     [](SampleScene& s) { s.core_skip[255] = std::uint8_t(s.core_skip[255] | 0x0F); }, Rule::bad_value, SectionKind::core_skip, 255},
    {"core skip level too low", [](SampleScene& s) { s.core_skip[0] = 0; }, Rule::bad_value, SectionKind::core_skip, 0},
    {"core skip one byte short", [](SampleScene& s) { s.core_skip.pop_back(); }, Rule::record_size, SectionKind::core_skip, 0},
    {"core skip for a changed occupancy", [](SampleScene& s) { s.occupancy[5] = gpu::NANO_BOX_INSIDE; }, Rule::bad_value,
     SectionKind::core_skip, 2},
    {"two media", [](SampleScene& s) { s.medium.push_back(s.medium[0]); }, Rule::record_size, SectionKind::medium, 0},
    {"medium box edge zero", [](SampleScene& s) { s.medium[0].region_min.w = 0; }, Rule::bad_value, SectionKind::medium, 12},
    {"medium region short of its boxes", [](SampleScene& s) { s.medium[0].region_max.x = 0; }, Rule::bad_value,
     SectionKind::medium, 16},
    {"medium recipe of squares", [](SampleScene& s) { s.medium[0].boxes.w = 0; }, Rule::bad_value, SectionKind::medium, 48},
    {"medium recipe out of range", [](SampleScene& s) { s.medium[0].boxes.w = 9; }, Rule::index_out_of_range,
     SectionKind::medium, 56},
    {"medium largest instance count", [](SampleScene& s) { s.medium[0].tiles.z = 2; }, Rule::bad_value, SectionKind::medium, 56},
    {"medium molecule beyond the next box", [](SampleScene& s) { s.medium[0].region_min.w = 2; }, Rule::bad_value,
     SectionKind::instances, 3 * 80 + 16},
    {"medium without exclusion fields",
     [](SampleScene& s) {
       s.exclusion_fields.clear();
       s.exclusion_values.clear();
     },
     Rule::missing_section, SectionKind::medium, 0},
    {"exclusion fields not one per compartment", [](SampleScene& s) { s.exclusion_fields.push_back(s.exclusion_fields[0]); },
     Rule::record_size, SectionKind::exclusion_fields, 0},
    {"exclusion field spacing zero", [](SampleScene& s) { s.exclusion_fields[0].origin.w = 0; }, Rule::bad_value,
     SectionKind::exclusion_fields, 12},
    {"exclusion field of one node per axis", [](SampleScene& s) { s.exclusion_fields[0].dims.y = 1; }, Rule::bad_value,
     SectionKind::exclusion_fields, 16},
    {"exclusion field beyond its values", [](SampleScene& s) { s.exclusion_fields[0].dims.w = 1; }, Rule::index_out_of_range,
     SectionKind::exclusion_fields, 28},
    {"exclusion field without its inverse spacing", [](SampleScene& s) { s.exclusion_fields[0].limits.z = 0; }, Rule::bad_value,
     SectionKind::exclusion_fields, 40},
    {"exclusion clamp below margin", [](SampleScene& s) { s.exclusion_fields[0].limits.y = 0.25f; }, Rule::bad_value,
     SectionKind::exclusion_fields, 36},
    {"exclusion value beyond the clamp", [](SampleScene& s) { s.exclusion_values[7] = 4; }, Rule::bad_value,
     SectionKind::exclusion_values, 7 * 4},
    {"exclusion value NaN", [](SampleScene& s) { s.exclusion_values[9] = kNaN; }, Rule::bad_value, SectionKind::exclusion_values,
     9 * 4},
    {"two scene records", [](SampleScene& s) { s.scene.push_back(s.scene[0]); }, Rule::record_size, SectionKind::scene, 0},
    {"field of view", [](SampleScene& s) { s.scene[0].camera_position.w = 0; }, Rule::bad_value, SectionKind::scene, 12},
    {"scene compartment index", [](SampleScene& s) { s.compartment_instances[1].compartment = 1; },
     Rule::index_out_of_range, SectionKind::compartment_instances, 64 + 48},
    {"NaN transform", [](SampleScene& s) { s.compartment_instances[0].transform[2].w = kNaN; }, Rule::non_finite,
     SectionKind::compartment_instances, 32 + 12},
    {"two effects records", [](SampleScene& s) { s.effects.push_back(s.effects[0]); }, Rule::record_size, SectionKind::effects, 0},
    {"NaN clip plane", [](SampleScene& s) { s.effects[0].clip_planes[0].w = kNaN; }, Rule::non_finite, SectionKind::effects, 12},
    {"clip plane normal not unit", [](SampleScene& s) { s.effects[0].clip_planes[0] = vec4(0, 0, 2, 1); }, Rule::bad_value,
     SectionKind::effects, 0},
    {"nine clip planes", [](SampleScene& s) { s.effects[0].clip_plane_count = 9; }, Rule::bad_value, SectionKind::effects, 240},
    {"plane past the count", [](SampleScene& s) { s.effects[0].clip_planes[3] = vec4(1, 0, 0, 0); }, Rule::nonzero_reserved,
     SectionKind::effects, 48},
    {"clip planes without the clipping flag",
     [](SampleScene& s) { s.scene[0].effect_flags &= ~package_flag(EffectId::clipping); }, Rule::bad_value, SectionKind::effects, 240},
    {"inverted clip box", [](SampleScene& s) { s.effects[0].clip_box_min.y = 20; }, Rule::inverted_aabb, SectionKind::effects, 132},
    {"clip box flag 2", [](SampleScene& s) { s.effects[0].clip_box_min.w = 2; }, Rule::bad_value, SectionKind::effects, 140},
    {"steady motion beside keyframes", [](SampleScene& s) { s.effects[0].velocity = vec4(1, 0, 0, 0); }, Rule::bad_value,
     SectionKind::effects, 160},
    {"spin axis not unit",
     [](SampleScene& s) {
       s.keyframes.clear();
       s.effects[0].spin = vec4(0, 2, 0, 10);
     },
     Rule::bad_value, SectionKind::effects, 160},
    {"AO rays 0", [](SampleScene& s) { s.effects[0].ambient_occlusion.x = 0; }, Rule::bad_value, SectionKind::effects, 208},
    {"AO rays 2.5", [](SampleScene& s) { s.effects[0].ambient_occlusion.x = 2.5f; }, Rule::bad_value, SectionKind::effects, 208},
    {"AO radius negative", [](SampleScene& s) { s.effects[0].ambient_occlusion.y = -1; }, Rule::bad_value, SectionKind::effects, 212},
    {"jitter without the flag", [](SampleScene& s) { s.effects[0].jitter = glm::vec2(5, 1); }, Rule::nonzero_reserved,
     SectionKind::effects, 192},
    {"jitter amplitude 200",
     [](SampleScene& s) {
       s.scene[0].effect_flags |= package_flag(EffectId::jitter);
       s.effects[0].jitter = glm::vec2(200, 1);
     },
     Rule::bad_value, SectionKind::effects, 192},
    {"shadow light zero", [](SampleScene& s) { s.effects[0].shadow_light = glm::vec3(0); }, Rule::bad_value, SectionKind::effects, 224},
    {"outline parameter while outlines are off", [](SampleScene& s) { s.effects[0].outline_crease_depth = 1; }, Rule::nonzero_reserved, SectionKind::effects, 248},
    {"effects reserved", [](SampleScene& s) { s.effects[0].clip_box_max.w = 1; }, Rule::nonzero_reserved, SectionKind::effects, 156},
    {"fog set while off", [](SampleScene& s) { s.effects[0].fog_strength = 0.5f; }, Rule::nonzero_reserved, SectionKind::effects, 220},
    {"outline width beyond 8 px",
     [](SampleScene& s) {
       s.scene[0].effect_flags |= package_flag(EffectId::outlines);
       s.effects[0].outline_width_pixels = 9, s.effects[0].outline_crease_depth = 5, s.effects[0].outline_colour = 0xff000000u;
     },
     Rule::bad_value, SectionKind::effects, 244},
    {"outline colour not opaque",
     [](SampleScene& s) {
       s.scene[0].effect_flags |= package_flag(EffectId::outlines);
       s.effects[0].outline_width_pixels = 1, s.effects[0].outline_crease_depth = 5, s.effects[0].outline_colour = 0x000000ffu;
     },
     Rule::bad_value, SectionKind::effects, 252},
    {"keyframe instance", [](SampleScene& s) { s.keyframes[1].instance = 2; }, Rule::index_out_of_range, SectionKind::keyframes,
     64 + 52},
    {"keyframe times not increasing", [](SampleScene& s) { s.keyframes[1].time = 0; }, Rule::bad_value, SectionKind::keyframes,
     64 + 48},
    {"keyframe negative time", [](SampleScene& s) { s.keyframes[0].time = -1; }, Rule::bad_value, SectionKind::keyframes, 48},
    {"keyframe singular", [](SampleScene& s) { s.keyframes[0].transform[1] = vec4(0, -1, 0, 3); }, Rule::bad_value,
     SectionKind::keyframes, 0},
    {"keyframe NaN", [](SampleScene& s) { s.keyframes[1].transform[2].y = kNaN; }, Rule::non_finite, SectionKind::keyframes,
     64 + 32 + 4},
    {"dropped keys not ascending", [](SampleScene& s) { s.dropped_copies[1] = 0; }, Rule::bad_value,
     SectionKind::dropped_copies, 4},
    {"dropped copy past the replication area", [](SampleScene& s) { s.dropped_copies[2] = 9u << 16; },
     Rule::index_out_of_range, SectionKind::dropped_copies, 8},
    {"dropped copy past the largest square", [](SampleScene& s) { s.dropped_copies[2] = (8u << 16) | 2u; },
     Rule::index_out_of_range, SectionKind::dropped_copies, 8},
    {"drop range past the keys", [](SampleScene& s) { s.triangle_drops[3].count = 2; }, Rule::index_out_of_range,
     SectionKind::triangle_drops, 3 * 8},
    {"drop ranges not parallel to triangles", [](SampleScene& s) { s.triangle_drops.pop_back(); }, Rule::record_size,
     SectionKind::triangle_drops, 0},
    {"drops on a mesh without membrane",
     [](SampleScene& s) { s.compartments[0].membrane_recipe = gpu::NANO_NO_INDEX; s.compartments[0].membrane_tile_count = 0; },
     Rule::index_out_of_range, SectionKind::dropped_copies, 0},
    {"bead ranges not parallel to molecules", [](SampleScene& s) { s.bead_ranges.pop_back(); }, Rule::record_size,
     SectionKind::bead_ranges, 0},
    {"molecule type without beads", [](SampleScene& s) { s.bead_ranges[1].count = 0; }, Rule::bad_value,
     SectionKind::bead_ranges, 8 + 4},
    {"bead range past the beads", [](SampleScene& s) { s.bead_ranges[1].count = 3; }, Rule::index_out_of_range,
     SectionKind::bead_ranges, 8},
    {"bead reports another type's atom", [](SampleScene& s) { s.beads[0].atom = 3; }, Rule::index_out_of_range,
     SectionKind::beads, 16},
    {"bead atom past the atoms", [](SampleScene& s) { s.beads[2].atom = 0xffffffffu; }, Rule::index_out_of_range,
     SectionKind::beads, 2 * 32 + 16},
    {"NaN bead", [](SampleScene& s) { s.beads[1].centre_radius.y = kNaN; }, Rule::non_finite, SectionKind::beads, 32 + 4},
    {"zero bead radius", [](SampleScene& s) { s.beads[1].centre_radius.w = 0; }, Rule::bad_value, SectionKind::beads,
     32 + 12},
    {"bead outside its type's box", [](SampleScene& s) { s.beads[0].centre_radius.x = 40; }, Rule::bad_value,
     SectionKind::beads, 0},
    {"bead smaller than the atom it reports", [](SampleScene& s) { s.beads[0].centre_radius.w = 1.2f; }, Rule::bad_value,
     SectionKind::beads, 12},
    {"beads merge fewer atoms than the type has", [](SampleScene& s) { s.beads[0].atom_count = 2; }, Rule::bad_value,
     SectionKind::bead_ranges, 0},
    {"bead merging no atom", [](SampleScene& s) { s.beads[2].atom_count = 0; }, Rule::bad_value, SectionKind::beads,
     2 * 32 + 20},
    {"bead reserved", [](SampleScene& s) { s.beads[1].reserved1 = 5; }, Rule::nonzero_reserved, SectionKind::beads,
     32 + 28},
    {"NUL in provenance", [](SampleScene& s) { s.provenance[5] = '\0'; }, Rule::bad_value, SectionKind::provenance, 5},
};

class Semantic : public ::testing::TestWithParam<Case> {};

TEST_P(Semantic, RejectedWithRuleSectionAndOffset) {
  const Case& c = GetParam();
  SampleScene s = make_sample_scene();
  c.corrupt(s);
  const std::vector<std::byte> bytes = build(s, Compression::none);
  const Package p = Package::from_bytes(bytes, "semantic.nup");
  try {
    validate_semantics(p);
    FAIL() << c.name << ": accepted";
  } catch (const PackageError& e) {
    EXPECT_EQ(e.code(), c.rule) << e.what();
    ASSERT_TRUE(e.location().section_kind.has_value()) << e.what();
    EXPECT_EQ(*e.location().section_kind, static_cast<std::uint32_t>(c.section)) << e.what();
    EXPECT_FALSE(e.location().decompressed);
    EXPECT_EQ(e.location().offset, p.entry(c.section)->offset + c.record_offset) << e.what();
    EXPECT_NE(std::string(e.what()).find("section " + section_kind_name(c.section)), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Corpus, Semantic, ::testing::ValuesIn(kCases), [](const auto& info) {
  std::string n = info.param.name;
  for (char& ch : n)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n;
});

TEST(SemanticCompressed, OffsetIsIntoTheDecompressedBytes) {
  SampleScene s = make_sample_scene();
  s.occupancy[300] = 7;
  const Package p = Package::from_bytes(build(s, Compression::zstd_if_smaller));
  ASSERT_EQ(p.entry(SectionKind::occupancy)->codec, static_cast<std::uint16_t>(Codec::zstd));
  try {
    validate_semantics(p);
    FAIL();
  } catch (const PackageError& e) {
    EXPECT_EQ(e.code(), Rule::bad_value);
    EXPECT_TRUE(e.location().decompressed);
    EXPECT_EQ(e.location().offset, 300u);
  }
}

TEST(SemanticMissing, ReferencedSectionsMustBePresent) {
  const SampleScene s = make_sample_scene();
  for (auto [without, user] : {std::pair{SectionKind::atoms, SectionKind::molecules},
                               {SectionKind::molecules, SectionKind::instances},
                               {SectionKind::instances, SectionKind::tiles2d},
                               {SectionKind::recipe_indices, SectionKind::recipes},
                               {SectionKind::meshes, SectionKind::compartments},
                               {SectionKind::triangle_shells, SectionKind::meshes},
                               {SectionKind::compartments, SectionKind::compartment_instances}}) {
    const Package p = Package::from_bytes(build_package(sections_of(s, Compression::none, without)));
    try {
      validate_semantics(p);
      ADD_FAILURE() << "without " << section_kind_name(without) << ": accepted";
    } catch (const PackageError& e) {
      EXPECT_EQ(e.code(), Rule::missing_section) << e.what();
      EXPECT_EQ(e.location().section_kind, static_cast<std::uint32_t>(user)) << e.what();
      EXPECT_NE(std::string(e.what()).find(section_kind_name(without)), std::string::npos) << e.what();
    }
  }
}

TEST(SemanticOptional, NoMembraneAndNoCoreGrid) {
  SampleScene s = make_sample_scene();
  s.compartments[0].membrane_recipe = gpu::NANO_NO_INDEX;
  s.compartments[0].soluble_recipe = gpu::NANO_NO_INDEX;
  s.compartments[0].grid_dims = glm::uvec4(0);
  s.compartments[0].core_masks = glm::uvec4(0);
  s.triangle_drops.assign(4, {0, 0});  // a mesh without membrane drops nothing
  s.dropped_copies.clear();
  refresh_core_skip(s);  // no core grid: no skip levels
  EXPECT_TRUE(s.core_skip.empty());
  EXPECT_NO_THROW(validate_semantics(Package::from_bytes(build(s))));
}

// A package may leave out the level of detail (before format 2.5), but not half of it.
TEST(SemanticOptional, NoBeads) {
  SampleScene s = make_sample_scene();
  s.beads.clear();
  s.bead_ranges.clear();
  EXPECT_NO_THROW(validate_semantics(Package::from_bytes(build(s))));
  for (const SectionKind without : {SectionKind::beads, SectionKind::bead_ranges}) {
    const SampleScene full = make_sample_scene();
    const Package p = Package::from_bytes(build_package(sections_of(full, Compression::none, without)));
    try {
      validate_semantics(p);
      ADD_FAILURE() << "without " << section_kind_name(without) << ": accepted";
    } catch (const PackageError& e) {
      EXPECT_EQ(e.code(), Rule::missing_section) << e.what();
    }
  }
}

// A package may leave out the drops (before format 2.2, or nothing dropped).
TEST(SemanticOptional, NoDroppedCopies) {
  SampleScene s = make_sample_scene();
  s.triangle_drops.clear();
  s.dropped_copies.clear();
  EXPECT_NO_THROW(validate_semantics(Package::from_bytes(build(s))));
}

// Format 2.3 stores the smooth surface's shape factor in scales.w; an older package must hold 0 there.
TEST(SemanticSmoothSurface, ShapeFactorInRangeFromFormat23On) {
  SampleScene s = make_sample_scene();
  s.compartments[0].scales.w = 0.75f;
  std::vector<std::byte> bytes = build(s);
  EXPECT_EQ(broken_rule(bytes), std::nullopt);
  put_le(bytes, 10, 2, 2);  // version 2.2
  seal_header(bytes);
  EXPECT_EQ(broken_rule(bytes), Rule::bad_value);
  s.compartments[0].scales.w = 0.f;
  bytes = build(s);
  put_le(bytes, 10, 2, 2);
  seal_header(bytes);
  EXPECT_EQ(broken_rule(bytes), std::nullopt);
}

// The valid counterpart of the seam cases: all six bits (edges 0-2, corners 3-5).
// The valid counterpart of "alternate in a Wang cube": a membrane square may hold alternates.
TEST(SemanticInstances, AlternatesInASquareAreValid) {
  SampleScene s = make_sample_scene();
  s.instances[0].flags = gpu::NANO_INSTANCE_ALTERNATE;
  EXPECT_NO_THROW(validate_semantics(Package::from_bytes(build(s))));
}

// Format 2.4 gave MoleculeInstance.flags its meaning; an older package must hold 0 there.
TEST(SemanticInstances, FlagsAreReservedBeforeFormat24) {
  SampleScene s = make_sample_scene();
  s.instances[0].flags = gpu::NANO_INSTANCE_ALTERNATE;
  std::vector<std::byte> bytes = build(s);
  put_le(bytes, 10, 2, 3);  // version 2.3
  seal_header(bytes);
  EXPECT_EQ(broken_rule(bytes), Rule::nonzero_reserved);
  s.instances[0].flags = 0;
  bytes = build(s);
  put_le(bytes, 10, 2, 3);
  seal_header(bytes);
  EXPECT_EQ(broken_rule(bytes), std::nullopt);
}

TEST(SemanticSeams, AllSixBitsAreValid) {
  SampleScene s = make_sample_scene();
  for (auto& shell : s.triangle_shells) shell.seam_edges = 63;
  EXPECT_NO_THROW(validate_semantics(Package::from_bytes(build(s))));
}

// The valid counterpart of the 33-molecule cases above: it is the mask width, not the cube size,
// that those reject.
TEST(SemanticCoreMasks, TwoWordsPerBoxForACubeOfMoreThan32Molecules) {
  SampleScene s = make_sample_scene();
  two_words_per_box(s);
  EXPECT_NO_THROW(validate_semantics(Package::from_bytes(build(s))));
}

}  // namespace
}  // namespace nano::format::test
