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
#include <optional>
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

// v at unit length, or nullopt when v is zero or not finite. As v / |v| when that is exact to the
// last bits; a vector so short or so long that its squares underflow or overflow is scaled by its
// largest component first (|v| of (1e-170, 0, 0) would be 0, of (3e-162, 0, 0) off by 5 %).
inline std::optional<glm::dvec3> unit_direction(const glm::dvec3& v) {
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) return std::nullopt;
  const double largest = std::fmax(std::fabs(v.x), std::fmax(std::fabs(v.y), std::fabs(v.z)));
  if (!(largest > 0.0)) return std::nullopt;
  const glm::dvec3 w = largest > 1e-150 && largest < 1e150 ? v : v / largest;
  return w / std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
}

// The largest side of the mesh's axis-aligned bounding box: what a scene's "diameter" sets.
inline double largest_side(const ProxyMesh& m) {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::dvec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::dvec3 size = hi - lo;
  return size.x > size.y ? (size.x > size.z ? size.x : size.z) : (size.y > size.z ? size.y : size.z);
}

}  // namespace nano::mesh
