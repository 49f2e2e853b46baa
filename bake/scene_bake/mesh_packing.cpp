#include "bake/scene_bake/mesh_packing.hpp"

#include <array>
#include <map>
#include <stdexcept>

#include <glm/common.hpp>

namespace nano::bake {

PackedMesh pack_mesh(const mesh::ProxyMesh& mesh) {
  if (!mesh.has_uvs() || !mesh.has_normals())
    throw std::invalid_argument("pack_mesh needs per-corner UVs and normals");
  PackedMesh packed;
  std::map<std::array<std::uint32_t, 3>, std::uint32_t> vertex_of_corner;
  packed.triangles.reserve(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    std::uint32_t local[3];
    for (int c = 0; c < 3; ++c) {
      const std::array<std::uint32_t, 3> key{mesh.triangles[t][c], mesh.uv_triangles[t][c], mesh.normal_triangles[t][c]};
      auto [it, inserted] = vertex_of_corner.try_emplace(key, static_cast<std::uint32_t>(packed.positions.size()));
      if (inserted) {
        packed.positions.emplace_back(glm::vec3(mesh.positions[key[0]]), 0.f);
        packed.uvs.emplace_back(mesh.uvs[key[1]]);
        packed.normals.emplace_back(glm::vec3(mesh.normals[key[2]]), 0.f);
      }
      local[c] = it->second;
    }
    packed.triangles.push_back(gpu::Triangle{local[0], local[1], local[2]});
  }
  if (!packed.positions.empty()) {
    packed.aabb_min = packed.aabb_max = glm::vec3(packed.positions[0]);
    for (const glm::vec4& p : packed.positions) {
      packed.aabb_min = glm::min(packed.aabb_min, glm::vec3(p));
      packed.aabb_max = glm::max(packed.aabb_max, glm::vec3(p));
    }
  }
  return packed;
}

}  // namespace nano::bake
