#include "common/effect_table.hpp"
#include "tests/format/sample_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "format/core_skip.hpp"
#include "format/draco_mesh_sections.hpp"

namespace nano::format::test {
namespace {

using glm::uvec4;
using glm::vec2;
using glm::vec4;

AtomInfo atom_info(const char* chain, const char* residue, int number, const char* name, const char* element) {
  AtomInfo a{};
  // NUL-padded fixed fields, not NUL-terminated when full (as the format says).
  std::memcpy(a.chain, chain, std::min(std::strlen(chain), sizeof a.chain));
  std::memcpy(a.residue_name, residue, std::min(std::strlen(residue), sizeof a.residue_name));
  std::memcpy(a.atom_name, name, std::min(std::strlen(name), sizeof a.atom_name));
  std::memcpy(a.element, element, std::min(std::strlen(element), sizeof a.element));
  a.residue_number = number;
  return a;
}

template <class T> SectionSource source(SectionKind kind, const std::vector<T>& v, Compression c) {
  return section_source(kind, std::span<const T>(v), c);
}

SectionSource text_source(SectionKind kind, const std::string& s, Compression c) {
  return section_source(kind, std::span<const char>(s.data(), s.size()), c);
}

}  // namespace

SampleScene make_sample_scene() {
  SampleScene s;
  s.strings = "haemoglobin2HHBband3membrane";
  // Type 0: three atoms; type 1: two atoms.
  s.molecules.push_back({vec4(-2, -1, -1, 2.5f), vec4(2, 1, 1.5f, 0), vec4(0, 0, 1, 0), vec4(0.8f, 0.1f, 0.1f, 1),
                         0, 3, 0, 11, 11, 4, 0, 0});
  s.molecules.push_back({vec4(-1, -1, -1, 1.8f), vec4(1, 1, 1, 0), vec4(0, 1, 0, 0), vec4(0.2f, 0.3f, 0.9f, 1),
                         3, 2, 15, 5, 0, 0, 0, 0});
  s.atoms = {{vec4(-1, 0, 0, 1)}, {vec4(1, 0, 0, 1)}, {vec4(0, 0, 0.5f, 1)}, {vec4(0, 0, 0, 1)}, {vec4(0.5f, 0, 0, 0.5f)}};
  s.atom_info = {atom_info("A", "HEM", 1, "FE", "FE"), atom_info("A", "HEM", 1, "NA", "N"), atom_info("B", "LYS", 42, "CA", "C"),
                 atom_info("C", "GLY", -3, "O", "O"), atom_info("C", "GLY", 7, "N", "N")};
  s.atom_info[2].insertion_code = 'A';
  const vec4 q(0, 0, 0.70710678f, 0.70710678f);
  s.instances = {{q, vec4(1, 1, 0, 0), vec4(0, 0, -1, 0), vec4(2, 2, 1, 0), 0, 0, 0, 0},
                 {vec4(0, 0, 0, 1), vec4(3, 3, 0, 0), vec4(2, 2, -1, 0), vec4(4, 4, 1, 0), 1, 0, 0, 0},
                 {vec4(0, 0, 0, 1), vec4(5, 5, 0, 0), vec4(4, 4, -1, 0), vec4(6, 6, 1, 0), 1, 0, 0, 0},
                 {q, vec4(2, 2, 2, 0), vec4(1, 1, 1, 0), vec4(3, 3, 3, 0), 0, 0, 0, 0}};
  s.tiles2d = {{uvec4(0, 1, 1, 0), vec4(6, 6, 4, 0), 0, 2, 0, 0}, {uvec4(1, 0, 0, 1), vec4(6, 6, 4, 0), 2, 1, 0, 0}};
  s.tiles3d = {{uvec4(0, 0, 1, 1), uvec4(0, 1, 0, 0), vec4(5, 5, 5, 0), 3, 1, 0, 0}};
  s.recipes = {{uvec4(2, 2, 1, gpu::NANO_RECIPE_2D), 0, 4, 0, 0}, {uvec4(1, 1, 2, gpu::NANO_RECIPE_3D), 4, 2, 0, 0}};
  s.recipe_indices = {0, 1, 1, 0, 0, 0};
  s.meshes = {{vec4(0, 0, 0, 0), vec4(1, 1, 1, 0), 0, 4, 0, 4}};
  // A tetrahedron on the Draco sections' grids and in their canonical order (draco_mesh_sections.hpp),
  // so the same scene can be written with Draco mesh sections.
  s.vertex_positions = {vec4(0, 0, 0, 0), vec4(0, 0, 1, 0), vec4(0, 1, 0, 0), vec4(1, 0, 0, 0)};
  s.vertex_normals = {snap_normal_to_grid(vec4(-1, -1, -1, 0)), vec4(0, 0, 1, 0), vec4(0, 1, 0, 0), vec4(1, 0, 0, 0)};
  s.vertex_uvs = {vec2(0, 0), vec2(1, 1), vec2(0, 1), vec2(1, 0)};
  s.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
  for (int t = 0; t < 4; ++t) s.triangle_shells.push_back({vec4(0, 0, 1, 1), 3.0f + t, 1.0f, 0.25f, 0});
  // An 8x8x8 core grid: mostly outside, so the occupancy section compresses.
  s.occupancy.assign(512, gpu::NANO_BOX_OUTSIDE);
  for (int i = 200; i < 260; ++i) s.occupancy[i] = gpu::NANO_BOX_INSIDE;
  s.occupancy[199] = s.occupancy[260] = gpu::NANO_BOX_BOUNDARY;
  s.compartments = {{vec4(0, 0, 0, 0.125f), uvec4(8, 8, 8, 0), vec4(100, 6, 5, 0), 0, 0, 2, 0, 0, 1, 1, 3, 3, 20, 8, 0,
                     uvec4(0, 2, 0, 0)}};
  // The two BOUNDARY boxes' keep-masks: the cube set's largest cube has one molecule, so one word
  // per box; box 199 keeps it, box 260 does not.
  s.boundary_boxes = {{199, 0}, {260, 1}};
  s.mask_words = {1, 0};
  // Membrane copies the baker dropped: triangle 1 drops slot 0's instance 1 and slot 4's instance
  // 0, triangle 3 slot 8's instance 1 (W x H = 3 x 3 slots, squares of at most 2 instances).
  s.triangle_drops = {{0, 0}, {0, 2}, {2, 0}, {2, 1}};
  s.dropped_copies = {1, 4u << 16, (8u << 16) | 1u};
  refresh_core_skip(s);
  // The level of detail: type 0's three atoms as one bead about their centroid (0, 0, 1/6),
  // reporting atom 2 (the nearest); type 1's two atoms as a bead each.
  s.beads = {{vec4(0, 0, 1.0f / 6, 2.02f), 2, 3, 0, 0}, {vec4(0, 0, 0, 1.001f), 3, 1, 0, 0}, {vec4(0.5f, 0, 0, 0.501f), 4, 1, 0, 0}};
  s.bead_ranges = {{0, 1}, {1, 2}};
  // A medium of the one cube over 8 x 8 x 8 boxes of 5 Å, and the compartment's exclusion field:
  // 5 x 5 x 5 nodes 1 Å apart, the distance from the point (0, 0, 0) less 1 Å, clamped to ±3.
  s.medium = {{vec4(-20, -20, -20, 5), vec4(20, 20, 20, 1), uvec4(8, 8, 8, 1), uvec4(0, 1, 1, 0)}};
  s.exclusion_fields = {{vec4(-2, -2, -2, 1), uvec4(5, 5, 5, 0), vec4(0.5f, 3, 1, 0)}};
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i)
        s.exclusion_values.push_back(std::clamp(std::sqrt(float((i - 2) * (i - 2) + (j - 2) * (j - 2) + (k - 2) * (k - 2))) - 1.0f, -3.0f, 3.0f));
  s.scene = {{vec4(0, 0, 10, 0.8f), vec4(0, 0, 0, 0), vec4(0, 1, 0, 0),
              package_flag(EffectId::ambient_occlusion) | package_flag(EffectId::shadows) | package_flag(EffectId::clipping) |
                  package_flag(EffectId::animation),
              0, 0, 0}};
  // Clipping by one plane and a box, AO and shadows; instance 1 keyframed (so no steady motion).
  gpu::SceneEffects e{};
  e.clip_planes[0] = vec4(0, 0, 1, -2);
  e.clip_plane_count = 1;
  e.clip_box_min = vec4(-10, -10, -10, 1);
  e.clip_box_max = vec4(60, 10, 10, 0);
  e.ambient_occlusion = glm::vec2(8, 40);
  e.shadow_light = glm::vec3(0, 0.6f, 0.8f);
  s.effects = {e};
  s.keyframes = {{{vec4(0, -1, 0, 50), vec4(1, 0, 0, 0), vec4(0, 0, 1, -5)}, 0.0f, 1, 0, 0},
                 {{vec4(-1, 0, 0, 50), vec4(0, -1, 0, 10), vec4(0, 0, 1, -5)}, 2.0f, 1, 0, 0}};
  s.compartment_instances = {{{vec4(1, 0, 0, 0), vec4(0, 1, 0, 0), vec4(0, 0, 1, 0)}, 0, 0, 0, 0},
                             {{vec4(0, -1, 0, 50), vec4(1, 0, 0, 0), vec4(0, 0, 1, -5)}, 0, 0, 0, 0}};
  s.provenance = R"({"baker":"nanobake 0.1.0","inputs":{"2HHB.cif":"xxh3:0123456789abcdef"},)"
                 R"("parameters":{"tile_size":6,"cube_size":5,"seed":1,"notes":"the same words again and again and again"}})";
  return s;
}

std::vector<SectionSource> sections_of(const SampleScene& s, Compression mesh_c, std::optional<SectionKind> without) {
  using K = SectionKind;
  // Draco serves the four mesh sections only; the others then take zstd where it pays.
  const Compression c = mesh_c == Compression::draco || mesh_c == Compression::draco_if_smaller ? Compression::zstd_if_smaller : mesh_c;
  std::vector<SectionSource> all = {
      text_source(K::strings, s.strings, c),
      source(K::molecules, s.molecules, c),
      source(K::atoms, s.atoms, c),
      source(K::atom_info, s.atom_info, c),
      source(K::tiles2d, s.tiles2d, c),
      source(K::tiles3d, s.tiles3d, c),
      source(K::instances, s.instances, c),
      source(K::recipes, s.recipes, c),
      source(K::recipe_indices, s.recipe_indices, c),
      source(K::meshes, s.meshes, c),
      source(K::vertex_positions, s.vertex_positions, mesh_c),
      source(K::vertex_normals, s.vertex_normals, mesh_c),
      source(K::vertex_uvs, s.vertex_uvs, mesh_c),
      source(K::triangles, s.triangles, mesh_c),
      source(K::triangle_shells, s.triangle_shells, c),
      source(K::compartments, s.compartments, c),
      source(K::occupancy, s.occupancy, c),
      source(K::scene, s.scene, c),
      source(K::compartment_instances, s.compartment_instances, c),
      text_source(K::provenance, s.provenance, c),
      source(K::boundary_boxes, s.boundary_boxes, c),
      source(K::mask_words, s.mask_words, c),
      source(K::effects, s.effects, c),
      source(K::keyframes, s.keyframes, c),
      source(K::triangle_drops, s.triangle_drops, c),
      source(K::dropped_copies, s.dropped_copies, c),
      source(K::beads, s.beads, c),
      source(K::bead_ranges, s.bead_ranges, c),
      source(K::core_skip, s.core_skip, c),
      source(K::medium, s.medium, c),
      source(K::exclusion_fields, s.exclusion_fields, c),
      source(K::exclusion_values, s.exclusion_values, c),
  };
  std::vector<SectionSource> out;
  for (const SectionSource& src : all)
    if (!without || src.kind != static_cast<std::uint32_t>(*without)) out.push_back(src);
  return out;
}

void refresh_core_skip(SampleScene& s) {
  s.core_skip = core_skip_section({s.compartments, s.occupancy, s.tiles3d, s.recipes, s.recipe_indices, s.boundary_boxes, s.mask_words});
}

MeshArrays grid_sphere(int rings, int segments, float radius) {
  constexpr float kPi = 3.14159265358979f;
  MeshArrays m;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const float theta = kPi * float(r) / float(rings), phi = 2 * kPi * float(s % segments) / float(segments);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      m.positions.push_back({snap_to_step(radius * n.x, 1.f / 32), snap_to_step(radius * n.y, 1.f / 32),
                             snap_to_step(radius * n.z, 1.f / 32), 0.f});
      m.normals.push_back(snap_normal_to_grid(vec4(n, 0)));
      m.uvs.push_back({snap_to_step(float(s) / float(segments), 0x1p-24f), snap_to_step(float(r) / float(rings), 0x1p-24f)});
    }
  const auto at = [&](int r, int s) { return std::uint32_t(r * (segments + 1) + s); };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      if (r > 0) m.triangles.push_back({at(r, s), at(r + 1, s), at(r, s + 1)});
      if (r + 1 < rings) m.triangles.push_back({at(r, s + 1), at(r + 1, s), at(r + 1, s + 1)});
    }
  return canonical_mesh_order(m);
}

std::vector<std::byte> build(const SampleScene& scene, Compression compression) {
  return build_package(sections_of(scene, compression));
}

SampleScene medium_only_sample_scene() {
  SampleScene scene = make_sample_scene();
  scene.compartments[0].membrane_recipe = scene.compartments[0].soluble_recipe = gpu::NANO_NO_INDEX;
  scene.compartments[0].core_masks = glm::uvec4(0);
  scene.triangle_drops.clear();
  scene.dropped_copies.clear();
  scene.boundary_boxes.clear();
  scene.mask_words.clear();
  refresh_core_skip(scene);
  return scene;
}

}  // namespace nano::format::test
