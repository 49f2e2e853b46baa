#pragma once
// Everything a package holds, as the records of shaders/shared/package_records.h, filled stage by
// stage and turned into sections at the end. Indices handed out by the add_* functions are the
// ones the records reference, so the validator's range checks hold by construction.
#include <cstdint>
#include <string>
#include <vector>

#include "bake/grid/soluble_masks.hpp"
#include "bake/scene_bake/mesh_packing.hpp"
#include "bake/scene_bake/medium_bake.hpp"
#include "bake/scene_bake/molecule_library.hpp"
#include "bake/scene_bake/wang_bake.hpp"
#include "format/records.hpp"
#include "format/writer.hpp"
#include "shared/package_records.h"

namespace nano::scene_bake {

struct TileRange {
  std::uint32_t first = 0, count = 0;
};

struct PackageContent {
  std::string strings;
  std::vector<gpu::MoleculeType> molecules;
  std::vector<gpu::Atom> atoms;
  std::vector<format::AtomInfo> atom_info;
  std::vector<gpu::Bead> beads;              // the level of detail (structure/coarse_beads.hpp)
  std::vector<gpu::BeadRange> bead_ranges;   // parallel to molecules
  std::vector<gpu::Tile2D> tiles2d;
  std::vector<gpu::Tile3D> tiles3d;
  std::vector<gpu::MoleculeInstance> instances;
  std::vector<gpu::Recipe> recipes;
  std::vector<std::uint32_t> recipe_indices;
  std::vector<gpu::Mesh> meshes;
  std::vector<glm::vec4> vertex_positions, vertex_normals;
  std::vector<glm::vec2> vertex_uvs;
  std::vector<gpu::Triangle> triangles;
  std::vector<gpu::TriangleShell> triangle_shells;
  std::vector<gpu::TriangleDrops> triangle_drops;  // parallel to triangles; written only if a copy is dropped
  std::vector<std::uint32_t> dropped_copies;
  std::vector<gpu::Compartment> compartments;
  std::vector<std::uint8_t> occupancy;
  std::vector<gpu::BoundaryBox> boundary_boxes;
  std::vector<std::uint32_t> mask_words;
  std::vector<std::uint8_t> core_skip;  // empty-space skipping of every core grid (format/core_skip.hpp)
  std::vector<gpu::Medium> medium;                     // none or one record (shaders/shared/medium.h)
  std::vector<gpu::ExclusionField> exclusion_fields;   // with a medium: parallel to compartments
  std::vector<float> exclusion_values;
  gpu::SceneSettings scene{};
  std::vector<gpu::SceneEffects> effects;           // none or one record
  std::vector<gpu::InstanceKeyframe> keyframes;     // ascending (instance, time)
  std::vector<gpu::CompartmentInstance> compartment_instances;
  std::string provenance;
  // How the four mesh sections are stored (format/writer.hpp): zstd, or Draco where smaller, or Draco.
  format::Compression mesh_compression = format::Compression::zstd_if_smaller;

  // Appends `text` to the string table; returns (offset, length).
  std::pair<std::uint32_t, std::uint32_t> add_string(const std::string& text);
  // Molecule types must be added in library order: record i is library molecule i. Adds the type's
  // atoms and its coarse beads.
  std::uint32_t add_molecule(const BakedMolecule& molecule);
  // A Wang set's tiles (2D or 3D by the set) and their instances, with tile-space AABBs from atoms.
  TileRange add_wang_set(const BakedWangSet& set, const std::vector<BakedMolecule>& library);
  // Recipe cells index the set's tiles; the package stores them as absolute record indices.
  std::uint32_t add_recipe(const tiles::TilingRecipe& recipe, const TileRange& set);
  // `dropped`: per triangle the ascending keys of the membrane copies it drops (empty: none).
  std::uint32_t add_mesh(const PackedMesh& mesh, const std::vector<gpu::TriangleShell>& shells,
                         const std::vector<std::vector<std::uint32_t>>& dropped = {});
  // The occupancy bytes of a grid; returns the offset of its first byte.
  std::uint32_t add_occupancy(const std::vector<std::uint8_t>& classes);
  // Boundary boxes with W = ceil(largest cube / 32) words each; returns (first record, count).
  std::pair<std::uint32_t, std::uint32_t> add_keep_masks(const grid::KeepMasks& masks, std::uint32_t largest_cube);

  // The medium over its cube set (added as a Wang set at `cubes`): its record, recipe and the
  // compartments' exclusion fields (in compartment order).
  void add_medium(const BakedMedium& medium, const TileRange& cubes, std::uint32_t largest_cube);

  // The skip levels of every core grid, once the compartments and their grids are all added.
  void add_core_skip();

  // Sections referencing the vectors above (which must outlive the returned spans).
  std::vector<format::SectionSource> sections() const;
};

}  // namespace nano::scene_bake
