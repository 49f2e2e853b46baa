#pragma once
// A compartment's core space: the grid over its mesh, which boxes hold solubles, the per-molecule
// keep-masks of boundary boxes, the cube recipe, and how many copies that represents.
#include <cstdint>
#include <vector>

#include "bake/grid/box_occupancy.hpp"
#include "bake/grid/soluble_masks.hpp"
#include "bake/mesh/proxy_mesh.hpp"
#include "bake/scene/scene_description.hpp"
#include "bake/scene_bake/molecule_library.hpp"
#include "bake/scene_bake/wang_bake.hpp"

namespace nano::scene_bake {

struct BakedCore {
  grid::BoxOccupancy occupancy;  // holds the grid
  grid::KeepMasks masks;
  tiles::TilingRecipe recipe;
  std::vector<std::uint64_t> copies_by_molecule;  // indexed like the molecule library
};

// The cube-space molecules of each cube of a set, with the bounding radius of their molecule type.
std::vector<grid::CubeContents> cube_contents(const BakedWangSet& cubes, const std::vector<BakedMolecule>& library);

// `shell_inner_height`: how far below the surface the membrane shell reaches (Å). A soluble is kept
// when its centre is inside the mesh and its bounding sphere stays that far plus the soluble's
// clearance away from the surface.
BakedCore bake_core(const mesh::ProxyMesh& mesh, const BakedWangSet& cubes, const scene::SolubleDescription& soluble,
                    const std::vector<BakedMolecule>& library, double shell_inner_height, std::uint64_t seed,
                    int threads);

}  // namespace nano::scene_bake
