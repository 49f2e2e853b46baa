#include "bake/scene_bake/medium_bake.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "bake/scene/transform.hpp"
#include "common/error.hpp"
#include "shaders/shared/medium.h"

namespace nano::scene_bake {
namespace {

// The volume (compartment Å³) where the field keeps nothing of threshold `needed`: cells whose
// interpolated centre value, less the margin, is below it (the field's own rule at cell centres).
double excluded_volume(const grid::ExclusionField& f, double needed) {
  std::size_t cells = 0;
  for (int k = 0; k + 1 < f.dims.z; ++k)
    for (int j = 0; j + 1 < f.dims.y; ++j)
      for (int i = 0; i + 1 < f.dims.x; ++i) {
        double sum = 0;
        for (int c = 0; c < 8; ++c) sum += f.values[f.node_index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1))];
        if (sum / 8.0 - f.margin < needed) ++cells;
      }
  return double(cells) * f.spacing * f.spacing * f.spacing;
}

double determinant(const scene::Matrix3x4& m) {
  const glm::dvec3 a(m[0]), b(m[1]), c(m[2]);
  return std::abs(a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x));
}

}  // namespace

std::vector<double> medium_copies_per_box(const tiles::TilingRecipe& recipe, const BakedWangSet& cubes, std::size_t library_size) {
  std::vector<double> per_box(library_size, 0.0);
  for (const std::uint32_t cell : recipe.cells)
    for (const tiles::Instance& instance : cubes.set.tiles.at(cell).instances) per_box[cubes.molecule_of_type.at(instance.type)] += 1.0;
  for (double& n : per_box) n /= double(recipe.cells.size());
  return per_box;
}

BakedMedium bake_medium(const scene::SceneDescription& scene, const scene::Box& region, const BakedWangSet& cubes,
                        const std::vector<BakedMolecule>& library, std::span<const MediumCompartment> compartments,
                        std::span<const scene::PlacedInstance> instances, std::uint64_t seed, int threads) {
  const scene::SolubleDescription& soluble = scene.solubles.at(scene.medium->soluble.index);
  BakedMedium m;
  m.box_edge = soluble.cube_size;
  m.clearance = soluble.clearance;
  const glm::dvec3 size = region.max - region.min;
  m.boxes = glm::uvec3(glm::max(glm::ceil(size / m.box_edge), glm::dvec3(1.0)));
  m.region = {region.min, region.min + glm::dvec3(m.boxes) * m.box_edge};
  // scene::check_medium_region refused an incomplete set before the heavy stages.
  if (!cubes.set.colouring.complete()) throw std::logic_error("a medium's cube set must be complete");
  m.recipe = tiles::make_tiling_recipe(cubes.set.colouring, {kMediumRecipeCells, kMediumRecipeCells, kMediumRecipeCells}, seed,
                                       /*periodic=*/true);

  // The reach the fields must cover: the largest medium copy plus the clearance.
  double largest = 0.0;
  for (const std::uint32_t molecule : cubes.molecule_of_type) largest = std::max(largest, library[molecule].properties.bounding_radius);
  m.fields.reserve(compartments.size());
  for (const MediumCompartment& c : compartments) {
    const grid::MeshSurface surface(*c.mesh, "compartment mesh");
    grid::ExclusionFieldRequest request;
    request.reach = c.reach;
    request.medium_reach = largest + soluble.clearance;
    request.threads = threads;
    m.fields.push_back(grid::bake_exclusion_field(surface, request));
  }

  // Copies: the region's boxes at the recipe's mean, less what each instance's field excludes.
  const std::vector<double> per_box = medium_copies_per_box(m.recipe, cubes, library.size());
  const double boxes = double(m.boxes.x) * m.boxes.y * m.boxes.z;
  const double box_volume = m.box_edge * m.box_edge * m.box_edge;
  for (std::size_t molecule = 0; molecule < library.size(); ++molecule) {
    if (per_box[molecule] == 0) continue;
    double excluded = 0;
    const double needed = library[molecule].properties.bounding_radius + soluble.clearance;
    std::vector<double> volume_of(compartments.size(), -1.0);  // per compartment, at this threshold
    for (const scene::PlacedInstance& instance : instances) {
      const std::size_t c = instance.compartment.index;
      if (volume_of[c] < 0) volume_of[c] = excluded_volume(m.fields[c], needed);
      excluded += volume_of[c] * determinant(instance.transform);
    }
    const double copies = std::max(0.0, per_box[molecule] * (boxes - excluded / box_volume));
    m.copies_in_region += per_box[molecule] * boxes;
    auto named = std::find_if(m.counts.begin(), m.counts.end(), [&](const auto& n) { return n.name == library[molecule].name; });
    if (named == m.counts.end()) named = m.counts.insert(m.counts.end(), {library[molecule].name, 0.0, 0.0});
    named->copies += copies;
    named->atoms += copies * double(library[molecule].atoms.size());
  }
  return m;
}

}  // namespace nano::scene_bake
