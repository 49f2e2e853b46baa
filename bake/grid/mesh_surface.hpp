#pragma once
// Inside/outside and distance queries against a closed proxy mesh, through CGAL (an AABB tree of
// the triangles and Side_of_triangle_mesh). This header exposes no CGAL type; all CGAL code of
// nano_grid lives in mesh_surface_cgal.cpp. Queries are const and safe from several threads.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "bake/mesh/proxy_mesh.hpp"

namespace nano::grid {

class MeshSurface {
public:
  // Throws nano::InputError (file = context) when the mesh is empty, is not a 2-manifold polygon
  // mesh, or is not closed. The mesh is copied; the argument need not outlive this object.
  explicit MeshSurface(const mesh::ProxyMesh& mesh, const std::string& context = "proxy mesh");
  ~MeshSurface();
  MeshSurface(const MeshSurface&) = delete;
  MeshSurface& operator=(const MeshSurface&) = delete;

  // The triangles queried (positions and triangles only; no UVs or normals).
  const mesh::ProxyMesh& mesh() const;

  // Strictly inside the closed surface (points on the surface are not). Works for non-convex meshes.
  bool contains(const glm::dvec3& p) const;
  double squared_distance(const glm::dvec3& p) const;
  // Indices (ascending) of the triangles that meet the closed box [lo, hi] (exact predicate).
  std::vector<std::uint32_t> triangles_meeting(const glm::dvec3& lo, const glm::dvec3& hi) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nano::grid
