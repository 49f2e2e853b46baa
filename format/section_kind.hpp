#pragma once
// The section kinds of a .nup package, their names and the record type each one holds.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "format/records.hpp"

namespace nano::format {

// Values are part of the file format: never renumber, only append (see docs/format.md).
enum class SectionKind : std::uint32_t {
  strings = 1,
  molecules = 2,
  atoms = 3,
  atom_info = 4,
  tiles2d = 5,
  tiles3d = 6,
  instances = 7,
  recipes = 8,
  recipe_indices = 9,
  meshes = 10,
  vertex_positions = 11,
  vertex_normals = 12,
  vertex_uvs = 13,
  triangles = 14,
  triangle_shells = 15,
  compartments = 16,
  occupancy = 17,
  scene = 18,
  compartment_instances = 19,
  provenance = 20,
  boundary_boxes = 21,
  mask_words = 22,
  effects = 23,    // format 2.1
  keyframes = 24,  // format 2.1
  triangle_drops = 25,   // format 2.2
  dropped_copies = 26,   // format 2.2
  beads = 27,            // format 2.5
  bead_ranges = 28,      // format 2.5
  draco_meshes = 29,     // format 2.6: the Draco streams the mesh sections of codec draco decode from
};

// Every kind this reader knows, in numeric order.
inline constexpr SectionKind kAllSectionKinds[] = {
    SectionKind::strings,         SectionKind::molecules,       SectionKind::atoms,
    SectionKind::atom_info,       SectionKind::tiles2d,         SectionKind::tiles3d,
    SectionKind::instances,       SectionKind::recipes,         SectionKind::recipe_indices,
    SectionKind::meshes,          SectionKind::vertex_positions, SectionKind::vertex_normals,
    SectionKind::vertex_uvs,      SectionKind::triangles,       SectionKind::triangle_shells,
    SectionKind::compartments,    SectionKind::occupancy,       SectionKind::scene,
    SectionKind::compartment_instances, SectionKind::provenance,  SectionKind::boundary_boxes,
    SectionKind::mask_words,      SectionKind::effects,         SectionKind::keyframes,
    SectionKind::triangle_drops,  SectionKind::dropped_copies,  SectionKind::beads,
    SectionKind::bead_ranges,     SectionKind::draco_meshes,
};

bool is_known_section_kind(std::uint32_t kind);
// "molecules", or "kind 4711" for a kind this reader does not know.
std::string section_kind_name(std::uint32_t kind);
inline std::string section_kind_name(SectionKind kind) { return section_kind_name(static_cast<std::uint32_t>(kind)); }
std::optional<SectionKind> section_kind_from_name(std::string_view name);
// Size of one record of the kind (1 for byte sections such as strings, occupancy and provenance).
std::uint64_t record_size(SectionKind kind);

// The record type of each kind, so Package::records<K>() hands out a span of the right type.
template <SectionKind K> struct RecordOf;
template <> struct RecordOf<SectionKind::strings> { using type = char; };
template <> struct RecordOf<SectionKind::molecules> { using type = gpu::MoleculeType; };
template <> struct RecordOf<SectionKind::atoms> { using type = gpu::Atom; };
template <> struct RecordOf<SectionKind::atom_info> { using type = AtomInfo; };
template <> struct RecordOf<SectionKind::tiles2d> { using type = gpu::Tile2D; };
template <> struct RecordOf<SectionKind::tiles3d> { using type = gpu::Tile3D; };
template <> struct RecordOf<SectionKind::instances> { using type = gpu::MoleculeInstance; };
template <> struct RecordOf<SectionKind::recipes> { using type = gpu::Recipe; };
template <> struct RecordOf<SectionKind::recipe_indices> { using type = std::uint32_t; };
template <> struct RecordOf<SectionKind::meshes> { using type = gpu::Mesh; };
template <> struct RecordOf<SectionKind::vertex_positions> { using type = glm::vec4; };
template <> struct RecordOf<SectionKind::vertex_normals> { using type = glm::vec4; };
template <> struct RecordOf<SectionKind::vertex_uvs> { using type = glm::vec2; };
template <> struct RecordOf<SectionKind::triangles> { using type = gpu::Triangle; };
template <> struct RecordOf<SectionKind::triangle_shells> { using type = gpu::TriangleShell; };
template <> struct RecordOf<SectionKind::compartments> { using type = gpu::Compartment; };
template <> struct RecordOf<SectionKind::occupancy> { using type = std::uint8_t; };
template <> struct RecordOf<SectionKind::scene> { using type = gpu::SceneSettings; };
template <> struct RecordOf<SectionKind::compartment_instances> { using type = gpu::CompartmentInstance; };
template <> struct RecordOf<SectionKind::provenance> { using type = char; };
template <> struct RecordOf<SectionKind::boundary_boxes> { using type = gpu::BoundaryBox; };
template <> struct RecordOf<SectionKind::mask_words> { using type = std::uint32_t; };
template <> struct RecordOf<SectionKind::effects> { using type = gpu::SceneEffects; };
template <> struct RecordOf<SectionKind::keyframes> { using type = gpu::InstanceKeyframe; };
template <> struct RecordOf<SectionKind::triangle_drops> { using type = gpu::TriangleDrops; };
template <> struct RecordOf<SectionKind::dropped_copies> { using type = std::uint32_t; };
template <> struct RecordOf<SectionKind::beads> { using type = gpu::Bead; };
template <> struct RecordOf<SectionKind::bead_ranges> { using type = gpu::BeadRange; };
template <> struct RecordOf<SectionKind::draco_meshes> { using type = std::uint8_t; };
template <SectionKind K> using record_t = typename RecordOf<K>::type;

}  // namespace nano::format
