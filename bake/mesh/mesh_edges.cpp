#include "bake/mesh/mesh_edges.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <utility>

namespace nano::mesh {

namespace {

class DisjointSets {
public:
  explicit DisjointSets(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(std::uint32_t x, std::uint32_t y) {
    x = find(x), y = find(y);
    if (x != y) parent_[std::max(x, y)] = std::min(x, y);  // the root is the lowest member
  }

private:
  std::vector<std::uint32_t> parent_;
};

glm::dvec2 uv_at(const ProxyMesh& mesh, const EdgeUse& use, std::uint32_t position) {
  for (int c = 0; c < 3; ++c)
    if (mesh.triangles[use.face][c] == position) return mesh.corner_uv(use.face, c);
  return glm::dvec2(0.0);  // unreachable: the edge's endpoints are corners of its faces
}

}  // namespace

std::vector<MeshEdge> collect_edges(const ProxyMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<EdgeUse>> uses;
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t from = mesh.triangles[f][c], to = mesh.triangles[f][(c + 1) % 3];
      if (from == to) continue;
      uses[{std::min(from, to), std::max(from, to)}].push_back({f, c, from < to});
    }
  }
  std::vector<MeshEdge> edges;
  edges.reserve(uses.size());
  for (auto& [key, list] : uses) edges.push_back({key.first, key.second, std::move(list)});
  return edges;
}

std::vector<NonManifoldVertex> non_manifold_vertices(const ProxyMesh& mesh, const std::vector<MeshEdge>& edges) {
  // Faces around a vertex v form one fan when they are linked through edges (v, w) used by
  // exactly those faces; count the groups with a small union-find over v's incident faces.
  std::vector<std::vector<std::uint32_t>> faces_at(mesh.positions.size());
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
    for (int c = 0; c < 3; ++c)
      if (faces_at[mesh.triangles[f][c]].empty() || faces_at[mesh.triangles[f][c]].back() != f)
        faces_at[mesh.triangles[f][c]].push_back(f);

  std::vector<std::vector<const MeshEdge*>> edges_at(mesh.positions.size());
  for (const MeshEdge& edge : edges) {
    edges_at[edge.a].push_back(&edge);
    edges_at[edge.b].push_back(&edge);
  }
  std::vector<NonManifoldVertex> result;
  for (std::uint32_t v = 0; v < mesh.positions.size(); ++v) {
    const auto& faces = faces_at[v];
    if (faces.size() < 2) continue;
    std::map<std::uint32_t, std::uint32_t> local;  // face -> local index
    for (std::uint32_t f : faces) local.emplace(f, static_cast<std::uint32_t>(local.size()));
    DisjointSets local_fans(local.size());
    for (const MeshEdge* edge : edges_at[v])
      for (std::size_t i = 1; i < edge->uses.size(); ++i)
        local_fans.unite(local[edge->uses[0].face], local[edge->uses[i].face]);
    int count = 0;
    for (std::uint32_t i = 0; i < local.size(); ++i) count += local_fans.find(i) == i;
    if (count > 1) result.push_back({v, faces.front(), count});
  }
  return result;
}

bool is_seam(const ProxyMesh& mesh, const MeshEdge& edge) {
  if (edge.uses.size() != 2) return false;
  const EdgeUse& first = edge.uses[0];
  const EdgeUse& second = edge.uses[1];
  return uv_at(mesh, first, edge.a) != uv_at(mesh, second, edge.a) ||
         uv_at(mesh, first, edge.b) != uv_at(mesh, second, edge.b);
}

std::vector<std::uint32_t> uv_charts(const ProxyMesh& mesh, const std::vector<MeshEdge>& edges) {
  DisjointSets charts(mesh.triangles.size());
  for (const MeshEdge& edge : edges)
    if (edge.uses.size() == 2 && !is_seam(mesh, edge)) charts.unite(edge.uses[0].face, edge.uses[1].face);
  std::vector<std::uint32_t> ids(mesh.triangles.size());
  std::map<std::uint32_t, std::uint32_t> dense;
  for (std::uint32_t f = 0; f < ids.size(); ++f)
    ids[f] = dense.emplace(charts.find(f), static_cast<std::uint32_t>(dense.size())).first->second;
  return ids;
}

}  // namespace nano::mesh
