#include "bake/scene_bake/wang_bake.hpp"

#include "bake/scene_bake/tile_set_cache.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bake/scene/scene_feasibility.hpp"
#include "bake/tiles/wang_sets.hpp"
#include "common/error.hpp"

namespace nano::scene_bake {
namespace {

constexpr double kSquareAngstromPerSquareMicrometre = 1e8;

// The set's own type list holds only the molecules it uses, in first-use order.
std::uint32_t local_type(BakedWangSet& baked, std::vector<tiles::MoleculeType>& types,
                         const std::vector<BakedMolecule>& library, std::size_t molecule) {
  for (std::uint32_t i = 0; i < baked.molecule_of_type.size(); ++i)
    if (baked.molecule_of_type[i] == molecule) return i;
  baked.molecule_of_type.push_back(static_cast<std::uint32_t>(molecule));
  types.push_back(to_tile_molecule(library[molecule]));
  return static_cast<std::uint32_t>(types.size() - 1);
}

// One entry per name, in first-appearance order: a patch's lipids are one kind of molecule to a reader.
void merge_densities_by_name(std::vector<tiles::MoleculeDensity>& densities) {
  std::vector<tiles::MoleculeDensity> merged;
  for (const tiles::MoleculeDensity& d : densities) {
    auto it = std::find_if(merged.begin(), merged.end(), [&](const tiles::MoleculeDensity& m) { return m.name == d.name; });
    if (it == merged.end()) {
      merged.push_back(d);
      continue;
    }
    it->requested += d.requested;
    it->achieved += d.achieved;
    it->copies_in_set += d.copies_in_set;
  }
  densities = std::move(merged);
}

// The packers name the molecule whose amount they cannot reach; the user wrote a key, which the
// scene file's name is put before (bake_scene).
template <class Entries, class Set>
[[noreturn]] void rethrow_at_amount(const InputError& e, const Entries& entries, const Set& set, const std::string& more) {
  for (std::size_t i = 0; i < entries.size(); ++i)
    if (e.where() == entries[i].molecule.name) throw InputError("", scene::amount_key(set, i), e.rule() + more);
  throw InputError(e.file(), e.where(), e.rule() + more);
}

int integer_power(int base, int exponent) {
  int r = 1;
  for (int i = 0; i < exponent; ++i) r *= base;
  return r;
}

}  // namespace

tiles::MoleculeType to_tile_molecule(const BakedMolecule& molecule) {
  tiles::MoleculeType type;
  type.name = molecule.name;
  type.atoms.reserve(molecule.atoms.size());
  for (const structure::Atom& a : molecule.atoms)
    type.atoms.push_back({glm::vec3(a.position), static_cast<float>(a.radius)});
  type.bounding_radius = static_cast<float>(molecule.properties.bounding_radius);
  type.up_axis = glm::vec3(molecule.up);
  return type;
}

double copies_per_um2_from_per_tile(double copies_per_tile, double tile_size) {
  return copies_per_tile / (tile_size * tile_size / kSquareAngstromPerSquareMicrometre);
}

BakedWangSet bake_membrane_tiles(const scene::MembraneDescription& membrane, const std::vector<BakedMolecule>& library,
                                 const BakedLipidPatch* patch, const tiles::SurfaceDistortion& surface,
                                 std::uint64_t seed, int threads, const std::optional<std::filesystem::path>& cache) {
  if (membrane.tiles != integer_power(membrane.edge_colours, 4))
    throw InputError("", "membranes." + membrane.name + ".tiles",
                     "Wang squares are generated as the complete set of colours^4 = " +
                         std::to_string(integer_power(membrane.edge_colours, 4)) + " tiles");
  BakedWangSet baked;
  tiles::MembraneTileRequest request;
  request.edge = static_cast<float>(membrane.tile_size);
  request.colours = membrane.edge_colours;
  request.seed = seed;
  request.budget.threads = threads;
  request.surface = surface;
  for (const scene::MembraneProtein& protein : membrane.proteins) {
    tiles::MembraneMolecule m;
    m.type = local_type(baked, request.types, library, protein.molecule.index);
    m.copies_per_um2 = protein.abundance.unit == scene::SurfaceAbundance::Unit::per_um2
                           ? protein.abundance.value
                           : copies_per_um2_from_per_tile(protein.abundance.value, membrane.tile_size);
    m.depth = static_cast<float>(protein.depth);
    m.lipids_displaced_on_surface = protein.per_compartment.has_value();
    baked.protein_types.push_back(m.type);
    request.molecules.push_back(m);
  }
  if (membrane.lipids) {
    tiles::LipidFill fill;
    fill.type = local_type(baked, request.types, library, membrane.lipids->molecule.index);
    fill.area_per_lipid = static_cast<float>(membrane.lipids->area_per_lipid);
    fill.leaflet_offset = static_cast<float>(membrane.lipids->leaflet_offset);
    request.lipids = fill;
  }
  if (patch) {
    tiles::LipidPatch lipids;
    lipids.period_x = static_cast<float>(patch->period_x);
    lipids.period_y = static_cast<float>(patch->period_y);
    lipids.clearance = static_cast<float>(patch->clearance);
    for (std::size_t i = 0; i < patch->molecules.size(); ++i)
      lipids.lipids.push_back({local_type(baked, request.types, library, patch->molecules[i]),
                               glm::vec3(patch->positions[i]), glm::quat(1.f, 0.f, 0.f, 0.f)});
    for (const BakedLipidPatch& species : patch->mix) {
      tiles::LipidSpecies mixed;
      mixed.outer = static_cast<float>(species.outer);
      mixed.inner = static_cast<float>(species.inner);
      for (std::size_t i = 0; i < species.molecules.size(); ++i)
        mixed.conformers.push_back({local_type(baked, request.types, library, species.molecules[i]),
                                    glm::vec3(species.positions[i]), glm::quat(1.f, 0.f, 0.f, 0.f)});
      lipids.mix.push_back(std::move(mixed));
    }
    request.lipid_patch = std::move(lipids);
  }
  baked.packed_rigid = surface.rigid();
  try {
    baked.set = cached_membrane_tiles(request, cache, baked.from_cache);
  } catch (const InputError& e) {
    // A density that fits a flat tile may not fit what the meshes do to it: say so, and what helps.
    char bounds[256];
    std::snprintf(bounds, sizeof bounds,
                  " (tiles packed to survive chart stretch %.3g, normals turning %.3g rad/Å and tilting %.3g "
                  "from their faces: a finer mesh lowers the tilt, a more even UV layout the stretch)",
                  1.0 + surface.lateral_stretch, surface.curvature, surface.tilt);
    rethrow_at_amount(e, membrane.proteins, membrane, bounds);
  }
  merge_densities_by_name(baked.set.densities);
  return baked;
}

BakedWangSet bake_soluble_cubes(const scene::SolubleDescription& soluble,
                                const std::vector<BakedMolecule>& library, std::uint64_t seed, int threads,
                                const std::optional<std::filesystem::path>& cache) {
  const int complete = integer_power(soluble.face_colours, 6);
  const int per_incoming = integer_power(soluble.face_colours, 3);
  if (soluble.cubes != complete && soluble.cubes % per_incoming != 0)
    throw InputError("", "solubles." + soluble.name + ".cubes",
                     "a cube set holds colours^6 = " + std::to_string(complete) + " cubes (complete) or a multiple of colours^3 = " +
                         std::to_string(per_incoming));
  BakedWangSet baked;
  tiles::SolubleCubeRequest request;
  request.edge = static_cast<float>(soluble.cube_size);
  request.colours = soluble.face_colours;
  request.variants = soluble.cubes == complete ? 0 : soluble.cubes / per_incoming;
  request.seed = seed;
  request.budget.threads = threads;
  for (const scene::SolubleMolecule& molecule : soluble.molecules) {
    tiles::SolubleMolecule m;
    m.type = local_type(baked, request.types, library, molecule.molecule.index);
    m.copies_per_um3 = molecule.abundance.unit == scene::VolumeAbundance::Unit::millimolar
                           ? tiles::copies_per_um3_from_millimolar(molecule.abundance.value)
                           : molecule.abundance.value;
    request.molecules.push_back(m);
  }
  try {
    baked.set = cached_soluble_cubes(request, cache, baked.from_cache);
  } catch (const InputError& e) {
    rethrow_at_amount(e, soluble.molecules, soluble, "");
  }
  return baked;
}

tiles::TilingRecipe membrane_recipe(const tiles::WangSet& set, double tile_uv_size, std::uint64_t seed) {
  const int cells = std::clamp(static_cast<int>(std::ceil(1.0 / tile_uv_size)), 1, kMaxRecipe2DCells);
  return tiles::make_tiling_recipe(set.colouring, {cells, cells, 1}, seed, /*periodic=*/true);
}

bool complete_cube_set(const scene::SolubleDescription& soluble) {
  return soluble.cubes == integer_power(soluble.face_colours, 6);
}

void check_recipe_covers(bool complete_set, std::array<int, 3> grid_dims, const std::string& soluble_name,
                         const scene::SolubleDescription* soluble) {
  const int largest = *std::max_element(grid_dims.begin(), grid_dims.end());
  if (largest <= kMaxRecipe3DCells || complete_set) return;
  std::string fix = "use the complete cube set (colours^6 cubes)";
  if (soluble) {
    // The grid spans less than `largest` boxes of the present size: this size keeps it within the limit.
    char size[64];
    std::snprintf(size, sizeof size, "%.0f", std::ceil(soluble->cube_size * largest / kMaxRecipe3DCells));
    fix = "use the complete cube set (\"cubes\": " + std::to_string(integer_power(soluble->face_colours, 6)) +
          "), or a \"cube_size\" of at least " + size + " Å";
  }
  throw InputError("", "solubles." + soluble_name + ".cubes",
                   "the core grid has " + std::to_string(largest) + " boxes along an axis, more than " +
                       std::to_string(kMaxRecipe3DCells) + ", so its recipe must repeat: " + fix);
}

tiles::TilingRecipe soluble_recipe(const tiles::WangSet& set, std::array<int, 3> grid_dims, std::uint64_t seed,
                                   const std::string& soluble_name) {
  const bool fits = std::all_of(grid_dims.begin(), grid_dims.end(), [](int d) { return d <= kMaxRecipe3DCells; });
  if (fits) return tiles::make_tiling_recipe(set.colouring, grid_dims, seed, /*periodic=*/set.colouring.complete());
  check_recipe_covers(set.colouring.complete(), grid_dims, soluble_name);
  std::array<int, 3> block{};
  for (int a = 0; a < 3; ++a) block[a] = std::min(grid_dims[a], kMaxRecipe3DCells);
  return tiles::make_tiling_recipe(set.colouring, block, seed, /*periodic=*/true);
}

}  // namespace nano::scene_bake
