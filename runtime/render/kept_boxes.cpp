#include "runtime/render/kept_boxes.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

#include "shared/render_scene.h"

namespace nano::render {

std::uint32_t kept_box_pack(const glm::dvec3& lo, const glm::dvec3& hi, float B) {
  // Steps on the very float grid the shader decodes (kept_box_unpack), moved outward until the
  // decoded corner holds the true one.
  const auto decoded = [B](std::uint32_t q) { return -B + float(q) * (3.0f * B / gpu::kKeptSteps); };
  std::uint32_t word = gpu::NANO_KEPT_ANY;
  for (int a = 0; a < 3; ++a) {
    const double unit = 3.0 * double(B) / gpu::kKeptSteps;
    auto q_lo = std::uint32_t(std::clamp(std::floor((lo[a] + B) / unit), 0.0, 31.0));
    while (q_lo > 0 && double(decoded(q_lo)) > lo[a]) --q_lo;
    auto q_hi = std::uint32_t(std::clamp(std::ceil((hi[a] + B) / unit), 0.0, 31.0));
    while (q_hi < 31 && double(decoded(q_hi)) < hi[a]) ++q_hi;
    word |= q_lo << (5 * a) | q_hi << (15 + 5 * a);
  }
  return word;
}

std::vector<std::uint32_t> kept_boxes(const format::PackageView& v, std::span<const double> type_radius) {
  std::vector<std::uint32_t> kept(v.boundary_boxes.size(), 0u);
  for (const gpu::Compartment& c : v.compartments) {
    if (c.soluble_recipe == gpu::NANO_NO_INDEX) continue;
    for (std::uint64_t r = c.core_masks.x; r < std::uint64_t{c.core_masks.x} + c.core_masks.y; ++r) {
      const std::uint32_t box = v.boundary_boxes[r].box;
      const std::uint32_t i = box % c.grid_dims.x, j = box / c.grid_dims.x % c.grid_dims.y, k = box / c.grid_dims.x / c.grid_dims.y;
      const gpu::Tile3D& cube = v.tiles3d[v.recipe_cell(c.soluble_recipe, i, j, k)];
      const std::uint32_t* words = v.mask_words.data() + v.boundary_boxes[r].first_word;
      glm::dvec3 lo(INFINITY), hi(-INFINITY);
      for (std::uint32_t m = 0; m < cube.instance_count; ++m) {
        if (((words[m / 32] >> (m % 32)) & 1u) == 0) continue;
        const gpu::MoleculeInstance& inst = v.instances[cube.first_instance + m];
        const double e = type_radius[inst.molecule_type] + 0.01;
        lo = glm::min(lo, glm::dvec3(inst.position) - e);
        hi = glm::max(hi, glm::dvec3(inst.position) + e);
      }
      if (lo.x <= hi.x) kept[r] = kept_box_pack(lo, hi, c.grid_min.w);
    }
  }
  return kept;
}

}  // namespace nano::render
