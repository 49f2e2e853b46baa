#include "bake/scene_bake/core_bake.hpp"

#include <algorithm>

#include "bake/grid/mesh_surface.hpp"

namespace nano::scene_bake {
namespace {

int wrap(int i, int n) { return ((i % n) + n) % n; }

}  // namespace

std::vector<grid::CubeContents> cube_contents(const BakedWangSet& cubes, const std::vector<BakedMolecule>& library) {
  std::vector<grid::CubeContents> contents;
  contents.reserve(cubes.set.tiles.size());
  for (const tiles::WangTile& cube : cubes.set.tiles) {
    grid::CubeContents molecules;
    molecules.reserve(cube.instances.size());
    for (const tiles::Instance& instance : cube.instances) {
      const std::uint32_t molecule = cubes.molecule_of_type[instance.type];
      molecules.push_back({glm::dvec3(instance.position), library[molecule].properties.bounding_radius, molecule});
    }
    contents.push_back(std::move(molecules));
  }
  return contents;
}

BakedCore bake_core(const mesh::ProxyMesh& mesh, const BakedWangSet& cubes, const scene::SolubleDescription& soluble,
                    const std::vector<BakedMolecule>& library, double shell_inner_height, std::uint64_t seed,
                    int threads) {
  const std::string context = "soluble '" + soluble.name + "'";
  const grid::MeshSurface surface(mesh, context);
  const grid::CoreGrid grid = grid::make_core_grid(mesh, soluble.cube_size, {}, context);

  BakedCore core;
  core.recipe = soluble_recipe(cubes.set, {grid.dims.x, grid.dims.y, grid.dims.z}, seed, soluble.name);
  const std::vector<grid::CubeContents> contents = cube_contents(cubes, library);
  double largest_radius = 0.0;
  for (const grid::CubeContents& cube : contents)
    for (const grid::CubeMolecule& m : cube) largest_radius = std::max(largest_radius, m.radius);

  const double keep_distance = shell_inner_height + soluble.clearance;
  core.occupancy = grid::classify_boxes(surface, grid, keep_distance + largest_radius, threads);
  const tiles::TilingRecipe& recipe = core.recipe;
  const grid::CubeRecipe cube_at = [&recipe](const glm::ivec3& b) {
    return recipe.at(wrap(b.x, recipe.size[0]), wrap(b.y, recipe.size[1]), wrap(b.z, recipe.size[2]));
  };
  core.masks = grid::compute_keep_masks(surface, core.occupancy, contents, cube_at, keep_distance, threads);
  std::vector<std::uint64_t> copies = grid::represented_copies(core.occupancy, contents, cube_at, core.masks);
  copies.resize(library.size(), 0);
  core.copies_by_molecule = std::move(copies);
  return core;
}

}  // namespace nano::scene_bake
