#include "runtime/render/kept_boxes.hpp"

#include <cmath>
#include <limits>

#include <glm/common.hpp>

namespace nano::render {

std::vector<gpu::KeptBox> kept_boxes(const format::PackageView& v, std::span<const double> type_radius) {
  std::vector<gpu::KeptBox> kept(v.boundary_boxes.size(), gpu::KeptBox{});
  const auto down = [](double x) { return std::nextafter(float(x), -std::numeric_limits<float>::infinity()); };
  const auto up = [](double x) { return std::nextafter(float(x), std::numeric_limits<float>::infinity()); };
  for (const gpu::Compartment& c : v.compartments) {
    if (c.soluble_recipe == gpu::NANO_NO_INDEX) continue;
    const gpu::Recipe& recipe = v.recipes[c.soluble_recipe];
    for (std::uint64_t r = c.core_masks.x; r < std::uint64_t{c.core_masks.x} + c.core_masks.y; ++r) {
      const std::uint32_t box = v.boundary_boxes[r].box;
      const std::uint32_t i = box % c.grid_dims.x, j = box / c.grid_dims.x % c.grid_dims.y, k = box / c.grid_dims.x / c.grid_dims.y;
      // Recipes wrap along every axis (render.comp's recipe_cell).
      const std::uint32_t cell = i % recipe.dims.x + recipe.dims.x * (j % recipe.dims.y + recipe.dims.y * (k % recipe.dims.z));
      const gpu::Tile3D& cube = v.tiles3d[v.recipe_indices[recipe.first_index + cell]];
      const std::uint32_t* words = v.mask_words.data() + v.boundary_boxes[r].first_word;
      glm::dvec3 lo(INFINITY), hi(-INFINITY);
      for (std::uint32_t m = 0; m < cube.instance_count; ++m) {
        if (((words[m / 32] >> (m % 32)) & 1u) == 0) continue;
        const gpu::MoleculeInstance& inst = v.instances[cube.first_instance + m];
        const double e = type_radius[inst.molecule_type] + 0.01;
        lo = glm::min(lo, glm::dvec3(inst.position) - e);
        hi = glm::max(hi, glm::dvec3(inst.position) + e);
      }
      if (!(lo.x <= hi.x)) continue;  // keeps nothing
      kept[r] = {glm::vec4(down(lo.x), down(lo.y), down(lo.z), 1.f), glm::vec4(up(hi.x), up(hi.y), up(hi.z), 0.f)};
    }
  }
  return kept;
}

}  // namespace nano::render
