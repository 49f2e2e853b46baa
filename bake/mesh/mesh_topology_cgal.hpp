#pragma once
// Exact predicates and solid properties through CGAL. This header exposes no CGAL type; the solid
// properties' CGAL code lives in mesh_topology_cgal.cpp so that only one translation unit pays its
// compile time (the predicates, which the readers use too, in exact_predicates_cgal.cpp).
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "bake/mesh/exact_predicates.hpp"
#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

struct SolidProperties {
  bool polygon_mesh = false;  // CGAL accepts the soup as an oriented 2-manifold (with or without border)
  bool closed = false;        // polygon mesh without border edges
  bool outward = false;       // closed and CGAL's is_outward_oriented
  double area = 0.0;
  std::optional<double> volume;  // signed; only for closed meshes
  // Pairs of faces whose interiors intersect; only computed when `closed` and `check_intersections`.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> self_intersections;
};

// Builds a CGAL Surface_mesh from the soup when PMP::is_polygon_soup_a_polygon_mesh allows it
// and measures it. Pass check_intersections = false when the mesh has degenerate triangles
// (CGAL's self-intersection test requires non-degenerate faces).
SolidProperties analyse_solid(const ProxyMesh& mesh, bool check_intersections);

// Per triangle, the distance from its centroid along its face normal — inward (−n) or outward (+n) —
// to the first triangle not sharing a corner with it that the ray meets: the local thickness of a closed outward mesh inside it,
// or the width of the gap outside it. INFINITY when the ray leaves the mesh; 0 for a degenerate face.
std::vector<double> distances_along_normals(const ProxyMesh& mesh, bool inward);

}  // namespace nano::mesh
