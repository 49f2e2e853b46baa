#include "bake/mesh/box_mesh.hpp"

#include <cmath>

#include <glm/geometric.hpp>

#include "common/error.hpp"

namespace nano::mesh {

ProxyMesh make_box_mesh(const glm::dvec3& size) {
  for (int a = 0; a < 3; ++a)
    if (!(size[a] > 0.0) || !std::isfinite(size[a]))
      throw InputError("generated box", "size", "each side must be positive and finite");
  ProxyMesh m;
  // Corner k has x = bit 0, y = bit 1, z = bit 2 of k (0: −size/2, 1: +size/2).
  for (int k = 0; k < 8; ++k)
    m.positions.push_back(0.5 * size * glm::dvec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
  // Each face as a quad counter-clockwise seen from outside, split along one diagonal.
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6},   // z−, z+
                                     {0, 1, 5, 4}, {2, 6, 7, 3},   // y−, y+
                                     {0, 4, 6, 2}, {1, 3, 7, 5}};  // x−, x+
  // UVs: each face its own cell of a 3 × 2 atlas (inset by a gutter), its corners counter-clockwise
  // in the cell as on the face, so the UVs wind as the faces do; normals: the face's own.
  constexpr double kCell = 1.0 / 3.0, kGutter = 0.02;
  const glm::dvec2 corner[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (std::uint32_t f = 0; f < 6; ++f) {
    const auto& q = quads[f];
    const glm::dvec2 origin((f % 3) * kCell, (f / 3) * kCell);
    const std::uint32_t uv0 = static_cast<std::uint32_t>(m.uvs.size());
    for (const glm::dvec2& c : corner) m.uvs.push_back(origin + kGutter + c * (kCell - 2.0 * kGutter));
    const glm::dvec3 a = m.positions[q[0]], b = m.positions[q[1]], d = m.positions[q[3]];
    m.normals.push_back(glm::normalize(glm::cross(b - a, d - a)));
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
    m.uv_triangles.push_back({uv0, uv0 + 1, uv0 + 2});
    m.uv_triangles.push_back({uv0, uv0 + 2, uv0 + 3});
    m.normal_triangles.push_back({f, f, f});
    m.normal_triangles.push_back({f, f, f});
  }
  return m;
}

}  // namespace nano::mesh
