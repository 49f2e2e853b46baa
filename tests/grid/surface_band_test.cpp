#include "bake/grid/surface_band.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "bake/mesh/rbc_mesh.hpp"
#include "bake/mesh/sphere_mesh.hpp"
#include "tests/grid/grid_oracles.hpp"

namespace nano::grid {
namespace {

// Every box's level against the brute-force distance from its centre to all triangles.
void expect_levels_match_brute_force(const mesh::ProxyMesh& m, double box_size, double clearance) {
  const CoreGrid g = make_core_grid(m, box_size);
  const std::vector<BandLevel> levels = mark_surface_band(m, g, clearance);
  ASSERT_EQ(levels.size(), g.box_count());
  const double hd = 0.5 * std::sqrt(3.0) * box_size, tol = 1e-6 * box_size;
  int near = 0, band = 0;
  for (BoxIndex i = 0; i < g.box_count(); ++i) {
    const double d = oracle::mesh_distance(m, g.box_centre(g.box_at(i)));
    const BandLevel l = levels[i];
    if (d <= hd - tol) {
      EXPECT_EQ(l, BandLevel::near) << i;
    } else if (d > hd + tol && d <= hd + clearance - tol) {
      EXPECT_EQ(l, BandLevel::band) << i;
    } else if (d > hd + clearance + tol) {
      EXPECT_EQ(l, BandLevel::far) << i;
    }
    near += l == BandLevel::near;
    band += l == BandLevel::band;
  }
  EXPECT_GT(near, 0);
  EXPECT_GT(band, 0);
}

TEST(SurfaceBand, SphereMatchesBruteForce) { expect_levels_match_brute_force(mesh::make_sphere_mesh(200, 1000.0), 150.0, 120.0); }
TEST(SurfaceBand, RbcMatchesBruteForce) { expect_levels_match_brute_force(mesh::make_rbc_mesh(400), 3000.0, 1500.0); }
TEST(SurfaceBand, ZeroClearanceHasNoBandOnlyBoxesBeyondTheDiagonal) {
  const mesh::ProxyMesh m = mesh::make_sphere_mesh(200, 1000.0);
  const CoreGrid g = make_core_grid(m, 400.0);
  const std::vector<BandLevel> levels = mark_surface_band(m, g, 0.0);
  for (BoxIndex i = 0; i < g.box_count(); ++i)
    if (oracle::mesh_distance(m, g.box_centre(g.box_at(i))) > 0.5 * std::sqrt(3.0) * 400.0 + 1e-6) {
      EXPECT_EQ(levels[i], BandLevel::far);
    }
}

}  // namespace
}  // namespace nano::grid
