#pragma once
// Per-box occupancy of a compartment's core grid: which boxes get a Wang cube of solubles.
#include <cstdint>
#include <vector>

#include "bake/grid/core_grid.hpp"
#include "bake/grid/mesh_surface.hpp"

namespace nano::grid {

enum class BoxClass : std::uint8_t {
  outside = 0,   // the closed box lies entirely outside the mesh: nothing is placed
  inside = 1,    // entirely inside and every point farther than `clearance` from the surface: the whole cube is kept
  boundary = 2,  // everything else (meets the surface, or inside within clearance): per-molecule keep-mask
};

struct BoxOccupancy {
  CoreGrid grid;
  double clearance = 0.0;
  std::vector<BoxClass> classes;  // one per box, by CoreGrid::linear_index
  std::uint64_t outside = 0, inside = 0, boundary = 0;

  BoxClass at(const glm::ivec3& b) const { return classes[grid.linear_index(b)]; }
};

// clearance: the caller passes (inner shell height + largest soluble bounding radius), so that
// any molecule whose centre lies in an INSIDE box clears the membrane shell with its whole sphere,
// including the part that sticks out into a neighbouring box.
// Conservative: a box may be called BOUNDARY needlessly (its centre is within half its diagonal
// + clearance of a triangle), but never INSIDE or OUTSIDE if it meets the surface, and never
// INSIDE if it comes within clearance of it. An OUTSIDE box near the surface stays OUTSIDE:
// the clearance band only matters where solubles may go.
// How: triangles are rasterised into the grid (surface_band.hpp); boxes the surface cannot
// cross keep one side along each run in x between crossable boxes, so one CGAL inside query
// per run decides a whole run (none for runs touching the grid's faces, which reach outside
// the mesh AABB). threads ≥ 1 spreads the rows over parallel_for; the result does not depend on it.
// Throws nano::InputError when clearance is negative or not finite, or the grid is empty.
BoxOccupancy classify_boxes(const MeshSurface& surface, const CoreGrid& grid, double clearance, int threads = 1);

}  // namespace nano::grid
