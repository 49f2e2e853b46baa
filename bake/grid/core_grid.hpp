#pragma once
// Core grid metadata (paper §"Core Space Construction"): a uniform grid of cubic boxes of edge
// box_size that strictly contains the proxy mesh's AABB. Nothing per box is stored here; every
// box position follows from (min, box_size, dims).
#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include "bake/mesh/proxy_mesh.hpp"

namespace nano::grid {

// Boxes are addressed by a linear index i + nx·(j + ny·k); the box limit keeps it in 32 bits.
using BoxIndex = std::uint32_t;

struct GridLimits {
  // Refuse grids larger than this; occupancy costs one byte per box, so the default (2^31)
  // already means 2 GiB. Lower it to enforce a memory budget.
  std::uint64_t max_boxes = std::uint64_t{1} << 31;
};

struct CoreGrid {
  glm::dvec3 min{0.0};  // model-space corner of box (0, 0, 0), Å
  double box_size = 0.0;
  glm::ivec3 dims{0};

  glm::dvec3 max() const { return min + box_size * glm::dvec3(dims); }
  std::uint64_t box_count() const;
  // Paper eq. b_ijk = floor((p − min) / S); half-open, so a point on a shared face belongs to the
  // box above it. Not clamped: the result may lie outside [0, dims).
  glm::ivec3 box_of(const glm::dvec3& p) const;
  bool contains(const glm::ivec3& b) const;
  glm::dvec3 box_min(const glm::ivec3& b) const { return min + box_size * glm::dvec3(b); }
  glm::dvec3 box_centre(const glm::ivec3& b) const { return min + box_size * (glm::dvec3(b) + 0.5); }
  BoxIndex linear_index(const glm::ivec3& b) const;
  glm::ivec3 box_at(BoxIndex index) const;
};

// Anchoring: dims = floor(extent / S) + 1 per axis, the fewest boxes that STRICTLY contain the
// mesh AABB, and the grid is centred on the mesh AABB (a margin in (0, S/2] on both sides). The
// strict margin guarantees that the first and last box of every row reach outside the mesh.
// Throws nano::InputError for an empty mesh, non-finite positions, box_size ≤ 0 or non-finite,
// and grids over limits.max_boxes.
CoreGrid make_core_grid(const mesh::ProxyMesh& mesh, double box_size, const GridLimits& limits = {},
                        const std::string& context = "core grid");

}  // namespace nano::grid
