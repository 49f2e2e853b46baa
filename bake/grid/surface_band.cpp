#include "bake/grid/surface_band.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "bake/grid/triangle_distance.hpp"

namespace nano::grid {

namespace {

struct Rasteriser {
  const CoreGrid& grid;
  std::vector<BandLevel>& levels;
  double near_reach, band_reach;  // distances from a box centre, rounding slack included
  glm::dvec3 a, b, c;

  // Blocks of boxes [lo, hi] are discarded when even their closest box centre is out of reach,
  // marked wholesale when their farthest one is near, and split along their longest axis otherwise.
  void visit(glm::ivec3 lo, glm::ivec3 hi) {
    const glm::dvec3 centre = grid.min + grid.box_size * (0.5 * glm::dvec3(lo + hi) + 0.5);
    const double spread = 0.5 * grid.box_size * glm::length(glm::dvec3(hi - lo));
    const double d = std::sqrt(squared_distance_to_triangle(centre, a, b, c));
    if (d - spread > band_reach) return;
    if (lo == hi || d + spread <= near_reach) {
      const BandLevel level = d + spread <= near_reach ? BandLevel::near : BandLevel::band;
      for (int k = lo.z; k <= hi.z; ++k)
        for (int j = lo.y; j <= hi.y; ++j)
          for (int i = lo.x; i <= hi.x; ++i) {
            BandLevel& slot = levels[grid.linear_index({i, j, k})];
            slot = std::max(slot, level);
          }
      return;
    }
    const glm::ivec3 size = hi - lo;
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
    glm::ivec3 mid_hi = hi, mid_lo = lo;
    mid_hi[axis] = lo[axis] + size[axis] / 2;
    mid_lo[axis] = mid_hi[axis] + 1;
    visit(lo, mid_hi);
    visit(mid_lo, hi);
  }
};

}  // namespace

std::vector<BandLevel> mark_surface_band(const mesh::ProxyMesh& mesh, const CoreGrid& grid, double clearance) {
  std::vector<BandLevel> levels(grid.box_count(), BandLevel::far);
  const double half_diagonal = 0.5 * std::sqrt(3.0) * grid.box_size;
  const double slack = 1e-9 * glm::length(grid.max() - grid.min);
  Rasteriser r{grid, levels, half_diagonal + slack, half_diagonal + clearance + slack, {}, {}, {}};
  for (const mesh::Triangle& t : mesh.triangles) {
    r.a = mesh.positions[t[0]];
    r.b = mesh.positions[t[1]];
    r.c = mesh.positions[t[2]];
    const glm::dvec3 reach(r.band_reach);
    const glm::ivec3 lo = glm::clamp(grid.box_of(glm::min(glm::min(r.a, r.b), r.c) - reach), glm::ivec3(0), grid.dims - 1);
    const glm::ivec3 hi = glm::clamp(grid.box_of(glm::max(glm::max(r.a, r.b), r.c) + reach), glm::ivec3(0), grid.dims - 1);
    r.visit(lo, hi);
  }
  return levels;
}

}  // namespace nano::grid
