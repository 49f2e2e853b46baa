#include "bake/scene_bake/mesh_packing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <map>
#include <stdexcept>

#include <glm/common.hpp>

#include "bake/shell/membrane_mapping.hpp"
#include "format/draco_mesh_sections.hpp"

namespace nano::scene_bake {

namespace {

format::MeshArrays arrays_of(const PackedMesh& packed) {
  return {packed.positions, packed.normals, packed.uvs, packed.triangles};
}

void set_bounds(PackedMesh& packed) {
  if (packed.positions.empty()) return;
  packed.aabb_min = packed.aabb_max = glm::vec3(packed.positions[0]);
  for (const glm::vec4& p : packed.positions) {
    packed.aabb_min = glm::min(packed.aabb_min, glm::vec3(p));
    packed.aabb_max = glm::max(packed.aabb_max, glm::vec3(p));
  }
}

}  // namespace

PackedMesh pack_mesh(const mesh::ProxyMesh& mesh) {
  if (!mesh.has_uvs() || !mesh.has_normals())  // invariant: the chart stage gave every packed mesh both
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
  set_bounds(packed);
  return packed;
}

float storage_position_step(const mesh::ProxyMesh& mesh) {
  double largest = 0.0;
  for (const glm::dvec3& p : mesh.positions) largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  return format::storage_position_step(largest);
}

mesh::ProxyMesh on_storage_grids(const mesh::ProxyMesh& input) {
  mesh::ProxyMesh snapped = input;
  const float step = storage_position_step(input);
  for (glm::dvec3& p : snapped.positions)
    p = {format::snap_to_step(p.x, step), format::snap_to_step(p.y, step), format::snap_to_step(p.z, step)};
  for (glm::dvec3& n : snapped.normals) n = glm::vec3(format::snap_normal_to_grid(glm::vec4(glm::vec3(n), 0.f)));
  for (glm::dvec2& uv : snapped.uvs) uv = glm::dvec2(shell::snap_uv(uv));
  const format::MeshArrays canonical = format::canonical_mesh_order(arrays_of(pack_mesh(snapped)));

  // Back to a proxy mesh: positions welded by their bits, UVs and normals per package vertex.
  mesh::ProxyMesh out;
  std::map<std::array<float, 3>, std::uint32_t> welded;
  std::vector<std::uint32_t> position_of(canonical.positions.size());
  for (std::size_t v = 0; v < canonical.positions.size(); ++v) {
    const glm::vec4& p = canonical.positions[v];
    const auto [it, added] = welded.try_emplace({p.x, p.y, p.z}, static_cast<std::uint32_t>(out.positions.size()));
    if (added) out.positions.emplace_back(glm::vec3(p));
    position_of[v] = it->second;
    out.normals.emplace_back(glm::vec3(canonical.normals[v]));
    out.uvs.emplace_back(canonical.uvs[v]);
  }
  for (const gpu::Triangle& t : canonical.triangles) {
    out.triangles.push_back({position_of[t.v0], position_of[t.v1], position_of[t.v2]});
    out.uv_triangles.push_back({t.v0, t.v1, t.v2});
  }
  out.normal_triangles = out.uv_triangles;
  return out;
}

PackedMesh pack_mesh_canonical(const mesh::ProxyMesh& mesh) {
  const PackedMesh packed = pack_mesh(mesh);
  const format::MeshArrays canonical = format::canonical_mesh_order(arrays_of(packed));
  // Same triangles in the same order, corner for corner: compare their corners' values.
  const auto same_corners = [&](std::size_t t) {
    const std::uint32_t a[3] = {packed.triangles[t].v0, packed.triangles[t].v1, packed.triangles[t].v2};
    const std::uint32_t b[3] = {canonical.triangles[t].v0, canonical.triangles[t].v1, canonical.triangles[t].v2};
    for (int c = 0; c < 3; ++c)
      if (packed.positions[a[c]] != canonical.positions[b[c]] || packed.normals[a[c]] != canonical.normals[b[c]] ||
          packed.uvs[a[c]] != canonical.uvs[b[c]])
        return false;
    return true;
  };
  if (canonical.triangles.size() != packed.triangles.size())
    throw std::logic_error("pack_mesh_canonical: canonical order dropped triangles");
  for (std::size_t t = 0; t < packed.triangles.size(); ++t)
    if (!same_corners(t)) throw std::logic_error("pack_mesh_canonical: the mesh is not in canonical order (triangle " + std::to_string(t) + ")");
  PackedMesh out{canonical.positions, canonical.normals, canonical.uvs, canonical.triangles};
  set_bounds(out);
  return out;
}

}  // namespace nano::scene_bake
