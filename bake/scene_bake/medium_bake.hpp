#pragma once
// The scene's medium as the package holds it (shaders/shared/medium.h): the region in whole boxes
// of the soluble's cube, a periodic recipe over the complete cube set (so nothing is stored per box
// of the region), one exclusion field per compartment, and what it holds. Copies are counted the way
// the rule keeps them, by volume: the region's boxes times the recipe's copies per box, less each
// instance's excluded volume at that molecule's threshold (an estimate, named so in the report; an
// exact count would test every one of ~10^9 copies).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "bake/grid/exclusion_field.hpp"
#include "bake/scene/medium_region.hpp"
#include "bake/scene/scene_description.hpp"
#include "bake/scene_bake/molecule_library.hpp"
#include "bake/scene_bake/wang_bake.hpp"
#include "bake/tiles/tiling_recipe.hpp"

namespace nano::scene_bake {

// What the medium must keep clear of in one compartment.
struct MediumCompartment {
  const mesh::ProxyMesh* mesh = nullptr;  // compartment space, as the package stores it
  std::vector<float> reach;               // per mesh triangle, how far its membrane copies reach (empty: none)
};

struct MediumMoleculeCount {
  std::string name;
  double copies = 0.0;  // estimated, as above
  double atoms = 0.0;
};

struct BakedMedium {
  scene::Box region;  // as filled: region_min + boxes · B
  glm::uvec3 boxes{0};
  double box_edge = 0.0;
  double clearance = 0.0;
  tiles::TilingRecipe recipe;
  std::vector<grid::ExclusionField> fields;  // per compartment
  std::vector<MediumMoleculeCount> counts;    // per molecule of the medium, by name
  double copies_in_region = 0.0;              // before any exclusion (exact: whole recipe periods plus the rest)
};

// The recipe's period per axis (cells); the region repeats it.
inline constexpr int kMediumRecipeCells = 16;

// `region` is the scene's region (scene::medium_region); `instances` the placed instances (their
// transforms, for the excluded volumes).
BakedMedium bake_medium(const scene::SceneDescription& scene, const scene::Box& region, const BakedWangSet& cubes,
                        const std::vector<BakedMolecule>& library, std::span<const MediumCompartment> compartments,
                        std::span<const scene::PlacedInstance> instances, std::uint64_t seed, int threads);

// The copies of each library molecule per box, averaged over the recipe (cube set types mapped to
// the library).
std::vector<double> medium_copies_per_box(const tiles::TilingRecipe& recipe, const BakedWangSet& cubes, std::size_t library_size);

}  // namespace nano::scene_bake
