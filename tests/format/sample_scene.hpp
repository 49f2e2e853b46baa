#pragma once
// A small but complete and consistent scene holding every section kind, as plain vectors the tests
// keep as the oracle for what was written.
#include <string>
#include <vector>

#include "format/draco_mesh_sections.hpp"
#include "format/writer.hpp"

namespace nano::format::test {

struct SampleScene {
  std::string strings;
  std::vector<gpu::MoleculeType> molecules;
  std::vector<gpu::Atom> atoms;
  std::vector<AtomInfo> atom_info;
  std::vector<gpu::Tile2D> tiles2d;
  std::vector<gpu::Tile3D> tiles3d;
  std::vector<gpu::MoleculeInstance> instances;
  std::vector<gpu::Recipe> recipes;
  std::vector<std::uint32_t> recipe_indices;
  std::vector<gpu::Mesh> meshes;
  std::vector<glm::vec4> vertex_positions;
  std::vector<glm::vec4> vertex_normals;
  std::vector<glm::vec2> vertex_uvs;
  std::vector<gpu::Triangle> triangles;
  std::vector<gpu::TriangleShell> triangle_shells;
  std::vector<gpu::Compartment> compartments;
  std::vector<std::uint8_t> occupancy;
  std::vector<gpu::SceneSettings> scene;
  std::vector<gpu::CompartmentInstance> compartment_instances;
  std::string provenance;
  std::vector<gpu::BoundaryBox> boundary_boxes;
  std::vector<std::uint32_t> mask_words;
  std::vector<gpu::TriangleDrops> triangle_drops;
  std::vector<std::uint32_t> dropped_copies;
  std::vector<gpu::SceneEffects> effects;
  std::vector<gpu::InstanceKeyframe> keyframes;
  std::vector<gpu::Bead> beads;
  std::vector<gpu::BeadRange> bead_ranges;
  std::vector<gpu::Medium> medium;
  std::vector<gpu::ExclusionField> exclusion_fields;
  std::vector<float> exclusion_values;
  std::vector<std::uint8_t> core_skip;  // derived by make_sample_scene; refresh_core_skip after changing the grid
};

// Derives s.core_skip again from the grid's occupancy, cubes and keep-masks (format/core_skip.hpp).
void refresh_core_skip(SampleScene& s);

SampleScene make_sample_scene();
// The sample scene without its membrane and core grid (made to test the format, not to place
// copies): its medium alone holds copies.
SampleScene medium_only_sample_scene();

// One SectionSource per non-empty section (spans into `scene`, which must outlive them), in kind
// order, optionally leaving one kind out.
std::vector<SectionSource> sections_of(const SampleScene& scene, Compression compression,
                                       std::optional<SectionKind> without = std::nullopt);

// A UV sphere of `rings` x `segments` quads on the Draco sections' grids (positions in 1/32 Å,
// UVs in 2^-24, octahedral normals) in canonical order, with a seam: the vertices of segment 0 exist
// twice, at u = 0 and u = 1, as a baker's would.
MeshArrays grid_sphere(int rings, int segments, float radius);

std::vector<std::byte> build(const SampleScene& scene, Compression compression = Compression::zstd_if_smaller);

}  // namespace nano::format::test
