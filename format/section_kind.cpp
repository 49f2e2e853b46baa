#include "format/section_kind.hpp"

#include <array>

namespace nano::format {
namespace {

struct KindInfo {
  SectionKind kind;
  std::string_view name;
  std::uint64_t record_size;
};

template <SectionKind K> constexpr KindInfo info(std::string_view name) {
  return {K, name, sizeof(record_t<K>)};
}

constexpr std::array kKinds = {
    info<SectionKind::strings>("strings"),
    info<SectionKind::molecules>("molecules"),
    info<SectionKind::atoms>("atoms"),
    info<SectionKind::atom_info>("atom_info"),
    info<SectionKind::tiles2d>("tiles2d"),
    info<SectionKind::tiles3d>("tiles3d"),
    info<SectionKind::instances>("instances"),
    info<SectionKind::recipes>("recipes"),
    info<SectionKind::recipe_indices>("recipe_indices"),
    info<SectionKind::meshes>("meshes"),
    info<SectionKind::vertex_positions>("vertex_positions"),
    info<SectionKind::vertex_normals>("vertex_normals"),
    info<SectionKind::vertex_uvs>("vertex_uvs"),
    info<SectionKind::triangles>("triangles"),
    info<SectionKind::triangle_shells>("triangle_shells"),
    info<SectionKind::compartments>("compartments"),
    info<SectionKind::occupancy>("occupancy"),
    info<SectionKind::scene>("scene"),
    info<SectionKind::compartment_instances>("compartment_instances"),
    info<SectionKind::provenance>("provenance"),
    info<SectionKind::boundary_boxes>("boundary_boxes"),
    info<SectionKind::mask_words>("mask_words"),
    info<SectionKind::effects>("effects"),
    info<SectionKind::keyframes>("keyframes"),
    info<SectionKind::triangle_drops>("triangle_drops"),
    info<SectionKind::dropped_copies>("dropped_copies"),
    info<SectionKind::beads>("beads"),
    info<SectionKind::bead_ranges>("bead_ranges"),
    info<SectionKind::draco_meshes>("draco_meshes"),
};
static_assert(kKinds.size() == std::size(kAllSectionKinds), "every kind has a name");

const KindInfo* find(std::uint32_t kind) {
  for (const KindInfo& k : kKinds)
    if (static_cast<std::uint32_t>(k.kind) == kind) return &k;
  return nullptr;
}

}  // namespace

bool is_known_section_kind(std::uint32_t kind) { return find(kind) != nullptr; }

std::string section_kind_name(std::uint32_t kind) {
  if (const KindInfo* k = find(kind)) return std::string(k->name);
  return "kind " + std::to_string(kind);
}

std::optional<SectionKind> section_kind_from_name(std::string_view name) {
  for (const KindInfo& k : kKinds)
    if (k.name == name) return k.kind;
  return std::nullopt;
}

std::uint64_t record_size(SectionKind kind) {
  const KindInfo* k = find(static_cast<std::uint32_t>(kind));
  return k ? k->record_size : 1;
}

}  // namespace nano::format
