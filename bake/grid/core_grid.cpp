#include "bake/grid/core_grid.hpp"

#include <cmath>
#include <limits>

#include <glm/common.hpp>

#include "common/error.hpp"

namespace nano::grid {

std::uint64_t CoreGrid::box_count() const {
  return static_cast<std::uint64_t>(dims.x) * static_cast<std::uint64_t>(dims.y) * static_cast<std::uint64_t>(dims.z);
}

glm::ivec3 CoreGrid::box_of(const glm::dvec3& p) const {
  const glm::dvec3 b = glm::floor((p - min) / box_size);
  return glm::ivec3(b);
}

bool CoreGrid::contains(const glm::ivec3& b) const {
  return b.x >= 0 && b.y >= 0 && b.z >= 0 && b.x < dims.x && b.y < dims.y && b.z < dims.z;
}

BoxIndex CoreGrid::linear_index(const glm::ivec3& b) const {
  return static_cast<BoxIndex>(b.x) +
         static_cast<BoxIndex>(dims.x) * (static_cast<BoxIndex>(b.y) + static_cast<BoxIndex>(dims.y) * static_cast<BoxIndex>(b.z));
}

glm::ivec3 CoreGrid::box_at(BoxIndex index) const {
  const auto nx = static_cast<BoxIndex>(dims.x), ny = static_cast<BoxIndex>(dims.y);
  return {static_cast<int>(index % nx), static_cast<int>((index / nx) % ny), static_cast<int>(index / (nx * ny))};
}

CoreGrid make_core_grid(const mesh::ProxyMesh& mesh, double box_size, const GridLimits& limits,
                        const std::string& context) {
  if (mesh.triangles.empty()) throw InputError(context, "mesh", "the mesh has no triangles");
  if (!(box_size > 0.0) || !std::isfinite(box_size))
    throw InputError(context, "box size", "box size must be positive and finite");
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const mesh::Triangle& t : mesh.triangles)
    for (std::uint32_t v : t) {
      if (v >= mesh.positions.size()) throw InputError(context, "mesh", "triangle index out of range");
      const glm::dvec3& p = mesh.positions[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw InputError(context, "mesh", "non-finite vertex position");
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }

  CoreGrid grid;
  grid.box_size = box_size;
  std::uint64_t count = 1;
  for (int a = 0; a < 3; ++a) {
    const double boxes = std::floor((hi[a] - lo[a]) / box_size) + 1.0;
    if (boxes > static_cast<double>(limits.max_boxes))
      throw InputError(context, "box size", "core grid would exceed the limit of " + std::to_string(limits.max_boxes) + " boxes");
    grid.dims[a] = static_cast<int>(boxes);
    const double centre = 0.5 * (lo[a] + hi[a]);
    grid.min[a] = centre - 0.5 * box_size * boxes;
    // Rounding may eat the margin when extent/S is just below an integer: add a box then.
    if (!(grid.min[a] < lo[a] && grid.min[a] + box_size * grid.dims[a] > hi[a])) {
      grid.dims[a] += 1;
      grid.min[a] = centre - 0.5 * box_size * grid.dims[a];
    }
    count *= static_cast<std::uint64_t>(grid.dims[a]);
    if (count > limits.max_boxes)
      throw InputError(context, "box size", "core grid would exceed the limit of " + std::to_string(limits.max_boxes) + " boxes");
  }
  return grid;
}

}  // namespace nano::grid
