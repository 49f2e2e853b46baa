#include "bake/mesh/sphere_mesh.hpp"

#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>

#include "bake/mesh/vertex_normals.hpp"
#include "common/error.hpp"

namespace nano::mesh {

namespace {

struct CubeFace {
  glm::ivec3 normal, u, v;  // u × v = normal, so counter-clockwise in (u, v) is outward
};

constexpr CubeFace cube_faces[6] = {
    {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
    {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
    {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}},
};

constexpr double atlas_cell = 1.0 / 3.0;
constexpr double atlas_gutter = 0.02;

}  // namespace

ProxyMesh make_sphere_mesh(int target_triangles, double radius) {
  if (target_triangles < 48)
    throw InputError("", "--triangles", "a cube-sphere needs at least 48 triangles, got " + std::to_string(target_triangles));
  if (!(radius > 0.0) || !std::isfinite(radius))
    throw InputError("", "--radius", "radius must be a positive number");
  const int n = std::max(2, static_cast<int>(std::lround(std::sqrt(target_triangles / 12.0))));

  ProxyMesh mesh;
  // Grid points are named by integer cube-lattice coordinates in [−n, n]³ (step 2 per cell), so
  // points on a shared cube edge get one position without any floating-point welding.
  std::map<std::array<int, 3>, std::uint32_t> position_of;
  auto position_index = [&](const glm::ivec3& lattice) {
    auto [it, inserted] = position_of.try_emplace({lattice.x, lattice.y, lattice.z}, mesh.positions.size());
    if (inserted) {
      const glm::dvec3 warped(std::tan(lattice.x * std::numbers::pi / (4.0 * n)),
                              std::tan(lattice.y * std::numbers::pi / (4.0 * n)),
                              std::tan(lattice.z * std::numbers::pi / (4.0 * n)));
      mesh.positions.push_back(radius * glm::normalize(warped));
    }
    return it->second;
  };

  for (int f = 0; f < 6; ++f) {
    const CubeFace& face = cube_faces[f];
    const glm::dvec2 chart_centre(atlas_cell * (f % 3 + 0.5), atlas_cell * (f / 3 + 0.5));
    const double chart_half = 0.5 * atlas_cell - atlas_gutter;
    const glm::dvec3 normal(face.normal), axis_u(face.u), axis_v(face.v);
    // Azimuthal equidistant about the face centre: θ / (π/4) along the azimuth.
    const auto chart_uv = [&](const glm::dvec3& p) {
      const glm::dvec2 tangent(glm::dot(p, axis_u), glm::dot(p, axis_v));
      const double across = glm::length(tangent);
      if (across == 0.0) return chart_centre;
      const double theta = std::atan2(across, glm::dot(p, normal));
      return chart_centre + chart_half * (theta / (std::numbers::pi / 4.0)) / across * tangent;
    };
    const auto first_uv = static_cast<std::uint32_t>(mesh.uvs.size());
    std::vector<std::uint32_t> positions((n + 1) * (n + 1));
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        positions[j * (n + 1) + i] = position_index(n * face.normal + (2 * i - n) * face.u + (2 * j - n) * face.v);
        mesh.uvs.push_back(chart_uv(mesh.positions[positions[j * (n + 1) + i]] / radius));
      }
    }
    auto corner = [&](int i, int j) { return std::pair(positions[j * (n + 1) + i], first_uv + j * (n + 1) + i); };
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const auto c00 = corner(i, j), c10 = corner(i + 1, j), c11 = corner(i + 1, j + 1), c01 = corner(i, j + 1);
        // Split cells along the diagonal that points away from the face centre, which keeps the
        // pattern symmetric under the cube's rotations and the triangles near the corners fat.
        const bool away = (2 * i + 1 - n) * (2 * j + 1 - n) > 0;
        const std::array<std::array<std::pair<std::uint32_t, std::uint32_t>, 3>, 2> cell =
            away ? std::array{std::array{c00, c10, c11}, std::array{c00, c11, c01}}
                 : std::array{std::array{c00, c10, c01}, std::array{c10, c11, c01}};
        for (const auto& tri : cell) {
          mesh.triangles.push_back({tri[0].first, tri[1].first, tri[2].first});
          mesh.uv_triangles.push_back({tri[0].second, tri[1].second, tri[2].second});
        }
      }
    }
  }
  compute_angle_weighted_normals(mesh);
  return mesh;
}

}  // namespace nano::mesh
