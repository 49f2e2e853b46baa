#pragma once
// The scene's membranes and solubles turned into Wang sets (bake/tiles), and the tiling recipes a
// compartment needs: a periodic 2D recipe over its UV square, a 3D recipe over its core grid.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "bake/scene/scene_description.hpp"
#include "bake/scene_bake/molecule_library.hpp"
#include "bake/tiles/collision_shape.hpp"
#include "bake/tiles/tiling_recipe.hpp"
#include "bake/tiles/wang_set.hpp"

namespace nano::scene_bake {

struct BakedWangSet {
  tiles::WangSet set;
  std::vector<std::uint32_t> molecule_of_type;  // the set's type index -> index into the library
  // Packed for no surface distortion at all: only a check of every copy on the surface keeps it clash-free.
  bool packed_rigid = true;
  // Set types of the membrane's proteins (not its lipids): dropped where no prism fits them.
  std::vector<std::uint32_t> protein_types;
  bool from_cache = false;  // the set was read from the bake cache (tile_set_cache.hpp), not packed
};

// A 2D recipe axis never needs more cells than this: beyond it the periodic recipe repeats.
inline constexpr int kMaxRecipe2DCells = 1024;
// A 3D recipe axis never holds more cells; larger core grids need a periodic (complete) cube set.
inline constexpr int kMaxRecipe3DCells = 64;

tiles::MoleculeType to_tile_molecule(const BakedMolecule& molecule);

// Copies per µm² of a per-tile abundance on tiles of edge `tile_size` Å.
double copies_per_um2_from_per_tile(double copies_per_tile, double tile_size);

// lateral_stretch: see tiles::MembraneTileRequest (mesh::chart_anisotropy − 1 of the meshes wearing it).
// `threads`: worker threads for the packing (the set does not depend on them).
// `patch`: the membrane's lipid patch (load_lipid_patch) when it has one, else nullptr. Densities
// of types sharing a name (a patch's lipids) are reported summed, under that name.
// `cache`: the bake cache's directory, where a set packed before for the same request is read
// (tile_set_cache.hpp); absent: always packed.
BakedWangSet bake_membrane_tiles(const scene::MembraneDescription& membrane, const std::vector<BakedMolecule>& library,
                                 const BakedLipidPatch* patch, const tiles::SurfaceDistortion& surface,
                                 std::uint64_t seed, int threads = 1,
                                 const std::optional<std::filesystem::path>& cache = std::nullopt);
BakedWangSet bake_soluble_cubes(const scene::SolubleDescription& soluble,
                                const std::vector<BakedMolecule>& library, std::uint64_t seed, int threads = 1,
                                const std::optional<std::filesystem::path>& cache = std::nullopt);

// Periodic recipe covering UV [0,1]² for tiles of UV size s (capped at kMaxRecipe2DCells per axis).
tiles::TilingRecipe membrane_recipe(const tiles::WangSet& set, double tile_uv_size, std::uint64_t seed);
// Refuses (InputError at solubles.NAME.cubes) a core grid of more than kMaxRecipe3DCells boxes along
// an axis for a cube set that is not complete (colours^6 cubes): its recipe would have to repeat.
// The bake asks before its heavy stages (check_nothing_emptied), soluble_recipe again when it builds.
// With `soluble`, the refusal names the values that work: its complete set's count and a cube size.
void check_recipe_covers(bool complete_set, std::array<int, 3> grid_dims, const std::string& soluble_name,
                         const scene::SolubleDescription* soluble = nullptr);
// Whether a soluble's `cubes` make the complete set of its face colours (colours^6).
bool complete_cube_set(const scene::SolubleDescription& soluble);

// Recipe over a core grid of `dims` boxes: the whole grid when it fits kMaxRecipe3DCells per axis,
// otherwise a periodic block (InputError naming the soluble when its cube set is not complete).
tiles::TilingRecipe soluble_recipe(const tiles::WangSet& set, std::array<int, 3> grid_dims, std::uint64_t seed,
                                   const std::string& soluble_name);

}  // namespace nano::scene_bake
