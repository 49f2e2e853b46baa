#pragma once
// Combinatorial structure of a triangle soup, read from position indices only (exact, no
// floating point): which faces use each edge and in which direction, the fans around each
// vertex, where the UV chart is cut (seams) and which faces form one connected UV chart.
#include <cstdint>
#include <vector>

#include "bake/mesh/proxy_mesh.hpp"

namespace nano::mesh {

struct EdgeUse {
  std::uint32_t face = 0;
  int corner = 0;        // the edge runs from this corner to the next one (counter-clockwise)
  bool forward = false;  // true when the face walks the edge from `a` to `b`
};

struct MeshEdge {
  std::uint32_t a = 0, b = 0;  // position indices, a < b
  std::vector<EdgeUse> uses;   // 1 use: border; 2: interior; more: non-manifold
};

// Every undirected edge of the soup, sorted by (a, b). Corner pairs with the same position index
// (a triangle with a repeated vertex) are not edges and are skipped.
std::vector<MeshEdge> collect_edges(const ProxyMesh& mesh);

struct NonManifoldVertex {
  std::uint32_t vertex = 0;
  std::uint32_t first_face = 0;  // lowest face index touching it, to point the user somewhere
  int fans = 0;                  // number of face fans joined at the vertex (> 1)
};

// Vertices whose incident faces do not form one edge-connected fan (e.g. two cones touching at
// their tips), which the shell builder cannot give one normal.
std::vector<NonManifoldVertex> non_manifold_vertices(const ProxyMesh& mesh, const std::vector<MeshEdge>& edges);

// An interior edge (exactly two uses) whose endpoints carry different UVs in its two faces.
// Requires mesh.has_uvs().
bool is_seam(const ProxyMesh& mesh, const MeshEdge& edge);

// Chart id per face: faces joined across interior edges that are not seams share an id.
// Ids are dense, 0-based, in order of the lowest face of each chart. Requires mesh.has_uvs().
std::vector<std::uint32_t> uv_charts(const ProxyMesh& mesh, const std::vector<MeshEdge>& edges);

}  // namespace nano::mesh
