#pragma once
// The package stores a mesh with per-vertex attributes (what a GPU index buffer wants), while the
// proxy mesh indexes UVs and normals per corner so seams can exist. Packing splits a position into
// one package vertex per distinct (position, UV, normal) corner combination.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "bake/mesh/proxy_mesh.hpp"
#include "shared/package_records.h"

namespace nano::bake {

struct PackedMesh {
  std::vector<glm::vec4> positions;  // xyz, w = 0
  std::vector<glm::vec4> normals;    // unit xyz, w = 0
  std::vector<glm::vec2> uvs;
  std::vector<gpu::Triangle> triangles;  // local vertex indices, same order as the proxy mesh
  glm::vec3 aabb_min{0.f}, aabb_max{0.f};
};

// Requires UVs and normals on every corner (a mesh that passed check-mesh has both).
PackedMesh pack_mesh(const mesh::ProxyMesh& mesh);

}  // namespace nano::bake
