#include "bake/grid/box_occupancy.hpp"

#include <algorithm>
#include <cmath>

#include "bake/grid/surface_band.hpp"
#include "common/error.hpp"
#include "common/parallel_for.hpp"

namespace nano::grid {

namespace {

// Classifies the boxes of row `row` (j, k) along x; rows are independent.
void classify_row(const CoreGrid& grid, const MeshSurface& surface, const std::vector<BandLevel>& band,
                  std::vector<BoxClass>& classes, std::size_t row) {
  const int nx = grid.dims.x;
  {
    const int j = static_cast<int>(row % grid.dims.y), k = static_cast<int>(row / grid.dims.y);
    const std::size_t base = grid.linear_index({0, j, k});
    int i = 0;
    while (i < nx) {
      if (band[base + i] == BandLevel::near) {
        classes[base + i] = BoxClass::boundary;
        ++i;
        continue;
      }
      int end = i;
      while (end < nx && band[base + end] != BandLevel::near) ++end;
      // No box of [i, end) meets the surface and neighbours share faces, so the run is on one side.
      const bool at_grid_face = i == 0 || end == nx;
      const bool inside = !at_grid_face && surface.contains(grid.box_centre({i, j, k}));
      for (int r = i; r < end; ++r)
        classes[base + r] = !inside ? BoxClass::outside
                          : band[base + r] == BandLevel::far ? BoxClass::inside : BoxClass::boundary;
      i = end;
    }
  }
}

}  // namespace

BoxOccupancy classify_boxes(const MeshSurface& surface, const CoreGrid& grid, double clearance, int threads) {
  if (!(clearance >= 0.0) || !std::isfinite(clearance))
    throw InputError("core grid", "clearance", "clearance must be finite and not negative");
  if (grid.box_count() == 0 || !(grid.box_size > 0.0))
    throw InputError("core grid", "grid", "the core grid is empty");
  BoxOccupancy result;
  result.grid = grid;
  result.clearance = clearance;
  const std::vector<BandLevel> band = mark_surface_band(surface.mesh(), grid, clearance);
  result.classes.assign(band.size(), BoxClass::outside);

  const std::size_t rows = static_cast<std::size_t>(grid.dims.y) * static_cast<std::size_t>(grid.dims.z);
  parallel_for(rows, threads, [&](std::size_t row) { classify_row(grid, surface, band, result.classes, row); });

  for (BoxClass c : result.classes) {
    if (c == BoxClass::outside) ++result.outside;
    else if (c == BoxClass::inside) ++result.inside;
    else ++result.boundary;
  }
  return result;
}

}  // namespace nano::grid
