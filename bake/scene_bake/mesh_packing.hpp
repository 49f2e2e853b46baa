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

namespace nano::scene_bake {

struct PackedMesh {
  std::vector<glm::vec4> positions;  // xyz, w = 0
  std::vector<glm::vec4> normals;    // unit xyz, w = 0
  std::vector<glm::vec2> uvs;
  std::vector<gpu::Triangle> triangles;  // local vertex indices, same order as the proxy mesh
  glm::vec3 aabb_min{0.f}, aabb_max{0.f};
};

// Requires UVs and normals on every corner (a mesh that passed check-mesh has both).
PackedMesh pack_mesh(const mesh::ProxyMesh& mesh);

// The mesh on the exact grids of Draco mesh sections (format/draco_mesh_sections.hpp), in their
// canonical order, so that what is baked is what a Draco package decodes to, bit for bit:
// positions snapped to storage_position_step (2^-5 Å for any cell), normals to the octahedral grid,
// UVs to the membrane's 2^-24 ownership grid (which the membrane bake snaps to anyway). Positions
// that snapping makes identical are welded, so check the result before baking it.
mesh::ProxyMesh on_storage_grids(const mesh::ProxyMesh& mesh);
// The position step on_storage_grids snaps `mesh` to (format::storage_position_step of its largest coordinate).
float storage_position_step(const mesh::ProxyMesh& mesh);

// pack_mesh in the canonical order, for a mesh from on_storage_grids (whose triangles are in that
// order already: the shells baked per triangle stay parallel). Throws std::logic_error otherwise.
PackedMesh pack_mesh_canonical(const mesh::ProxyMesh& mesh);

}  // namespace nano::scene_bake
