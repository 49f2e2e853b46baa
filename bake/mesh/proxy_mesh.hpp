#pragma once
// The proxy mesh every later bake stage reads: a triangle soup with indexed attributes.
// UVs and normals are indexed per CORNER (3 indices per triangle, as in OBJ), so a UV seam is
// simply two triangles that share a position but not a UV index. A per-vertex attribute is the
// special case uv_triangles == triangles. Positions are welded: no two entries are bit-identical,
// so topology (borders, non-manifold edges) can be read off the position indices.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace nano::mesh {

using Triangle = std::array<std::uint32_t, 3>;

struct ProxyMesh {
  std::vector<glm::dvec3> positions;
  std::vector<Triangle> triangles;         // indices into positions, counter-clockwise = outward

  std::vector<glm::dvec2> uvs;             // empty when the mesh has no UVs
  std::vector<Triangle> uv_triangles;      // per-corner indices into uvs; same size as triangles or empty

  std::vector<glm::dvec3> normals;         // unit vectors
  std::vector<Triangle> normal_triangles;  // per-corner indices into normals; same size as triangles or empty

  bool has_uvs() const { return !uv_triangles.empty(); }
  bool has_normals() const { return !normal_triangles.empty(); }

  glm::dvec3 corner_position(std::size_t t, int c) const { return positions[triangles[t][c]]; }
  glm::dvec2 corner_uv(std::size_t t, int c) const { return uvs[uv_triangles[t][c]]; }
  glm::dvec3 corner_normal(std::size_t t, int c) const { return normals[normal_triangles[t][c]]; }
};

// The largest side of the mesh's axis-aligned bounding box: what a scene's "diameter" sets.
inline double largest_side(const ProxyMesh& m) {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::dvec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::dvec3 size = hi - lo;
  return size.x > size.y ? (size.x > size.z ? size.x : size.z) : (size.y > size.z ? size.y : size.z);
}

}  // namespace nano::mesh
