#pragma once
// How the UV chart maps onto the surface (ALGORITHMS.md §1): per triangle the Jacobian
// J = F·E⁻¹ of the affine map UV → world, its singular values, the global scale k, and the
// replication-area size W×H that tiles of UV size s need.
#include <array>
#include <optional>

#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

struct UvJacobian {
  glm::dvec3 du;  // ∂X/∂u: world displacement per unit of u
  glm::dvec3 dv;  // ∂X/∂v
};

struct SingularValues {
  double major = 0.0;  // σ1, the largest stretch
  double minor = 0.0;  // σ2 ≤ σ1
};

double world_area(const ProxyMesh& mesh, std::size_t triangle);
// Positive when the UV corners run counter-clockwise. Floating point: use the exact
// orientation in mesh_topology_cgal.hpp where the sign decides something.
double uv_signed_area(const ProxyMesh& mesh, std::size_t triangle);

// J = F·E⁻¹ with F = [P1−P0 | P2−P0], E = [t1−t0 | t2−t0]; nullopt when det E == 0.
std::optional<UvJacobian> uv_jacobian(const std::array<glm::dvec3, 3>& world,
                                      const std::array<glm::dvec2, 3>& uv);
std::optional<UvJacobian> uv_jacobian(const ProxyMesh& mesh, std::size_t triangle);

// Singular values of the 3×2 matrix [du | dv], from the eigenvalues of the 2×2 Gram matrix.
SingularValues singular_values(const UvJacobian& j);

// k = sqrt(Σ world area / Σ |UV area|): world length per unit of UV on average, so that J/k has
// singular values near 1 where the chart is faithful. 0 if the mesh has no UV area.
double uv_scale(const ProxyMesh& mesh);

// The smallest stretch σ2 of J over all triangles with a usable chart (Å per UV unit): used as the
// tile scale, the UV→surface map never compresses a tile in any direction, so rigid molecules packed
// collision-free in tile space stay collision-free on the surface (they only spread where σ > it).
// 0 if no triangle has a usable chart.
double smallest_stretch(const ProxyMesh& mesh);

// The largest stretch σ1 over triangles with a usable chart divided by smallest_stretch: with the
// tile scale set to the smallest stretch, the in-plane map of every triangle has singular values in
// [1, chart_anisotropy]. 0 if no triangle has a usable chart.
double chart_anisotropy(const ProxyMesh& mesh);

// Tiles of UV size s needed along one axis to cover an extent: ceil(extent / s) + 1, the +1
// because a triangle's UV box rarely starts on a tile boundary.
int tiles_spanning(double extent, double s);

// Per-triangle UV box extent in tiles (u, v).
std::array<int, 2> triangle_tile_span(const ProxyMesh& mesh, std::size_t triangle, double s);

// W×H: the maximum of triangle_tile_span over all triangles.
std::array<int, 2> replication_area(const ProxyMesh& mesh, double s);

}  // namespace nano::mesh
