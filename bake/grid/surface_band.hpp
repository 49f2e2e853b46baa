#pragma once
// Which boxes lie near the surface, found by rasterising each triangle into the grid (no
// per-box query over the whole grid): the work is proportional to the boxes near the surface.
#include <cstdint>
#include <vector>

#include "bake/grid/core_grid.hpp"
#include "bake/mesh/proxy_mesh.hpp"

namespace nano::grid {

enum class BandLevel : std::uint8_t {
  far = 0,   // box centre farther than half_diagonal + clearance from every triangle
  band = 1,  // within half_diagonal + clearance, but farther than half_diagonal: the surface misses the box
  near = 2,  // box centre within half_diagonal of a triangle: the surface may cross the box
};

// One level per box (linear index). Conservative by a relative 1e-9 of the grid extent, so
// rounding can only move a box to a higher level, never lower. clearance ≥ 0.
std::vector<BandLevel> mark_surface_band(const mesh::ProxyMesh& mesh, const CoreGrid& grid, double clearance);

}  // namespace nano::grid
