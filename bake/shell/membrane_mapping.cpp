#include "bake/shell/membrane_mapping.hpp"

#include <algorithm>
#include <cmath>

#include "bake/mesh/mesh_edges.hpp"
#include "common/error.hpp"

namespace nano::shell {

namespace {

constexpr double kGridStep = 0x1.0p-24;  // ownership grid (ownership.h kOwnQuantScale)
constexpr double kUvLimit = 16.0;        // own_quantize clamps beyond

[[noreturn]] void fail(const std::string& context, const std::string& where, const std::string& rule) {
  throw InputError(context, where, rule);
}

void check_inputs(const mesh::ProxyMesh& mesh, const tiles::WangSet& set, const tiles::TilingRecipe& recipe, double k,
                  const std::string& context, float smooth) {
  if (!(smooth >= 0.f && smooth <= 1.f)) fail(context, "smooth", "the surface's shape factor must lie in [0, 1]");
  if (!mesh.has_uvs() || mesh.uv_triangles.size() != mesh.triangles.size())
    fail(context, "mesh", "the membrane mapping needs per-corner UVs on every triangle");
  if (!mesh.has_normals() || mesh.normal_triangles.size() != mesh.triangles.size())
    fail(context, "mesh", "the membrane mapping needs per-corner normals on every triangle");
  if (set.dims != 2) fail(context, "tile set", "the membrane needs a Wang square set (dims 2)");
  if (!(set.edge > 0.f) || !std::isfinite(set.edge)) fail(context, "tile set", "tile edge must be positive and finite");
  if (!(k > 0.0) || !std::isfinite(k)) fail(context, "scale", "global UV scale k must be positive and finite");
  if (recipe.dims != 2 || recipe.size[0] <= 0 || recipe.size[1] <= 0 || recipe.size[2] != 1 ||
      recipe.cells.size() != static_cast<std::size_t>(recipe.size[0]) * recipe.size[1])
    fail(context, "recipe", "the membrane needs a non-empty 2D recipe");
  for (std::size_t c = 0; c < recipe.cells.size(); ++c)
    if (recipe.cells[c] >= set.tiles.size())
      fail(context, "recipe cell " + std::to_string(c), "names tile " + std::to_string(recipe.cells[c]) +
                                                           " of a set with " + std::to_string(set.tiles.size()));
}

std::vector<glm::vec2> snap_mesh_uvs(const mesh::ProxyMesh& mesh, const std::string& context) {
  std::vector<glm::vec2> snapped;
  snapped.reserve(mesh.uvs.size());
  for (std::size_t i = 0; i < mesh.uvs.size(); ++i) {
    const glm::dvec2 uv = mesh.uvs[i];
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y) || std::abs(uv.x) >= kUvLimit || std::abs(uv.y) >= kUvLimit)
      fail(context, "uv " + std::to_string(i), "UVs must be finite with |u|, |v| < 16 (ownership grid)");
    snapped.push_back(snap_uv(uv));
  }
  return snapped;
}

// Seam-rule radii: each type's bounding radius (the package's aabb_min.w), checked to cover its
// atoms about the origin (the proof in seam.h needs it).
std::vector<float> type_radii(const tiles::WangSet& set, const std::vector<tiles::MoleculeType>& types,
                              const std::string& context) {
  std::vector<float> radii(types.size(), 0.f);
  std::vector<bool> used(types.size(), false);
  for (std::size_t t = 0; t < set.tiles.size(); ++t)
    for (std::size_t i = 0; i < set.tiles[t].instances.size(); ++i) {
      const std::uint32_t type = set.tiles[t].instances[i].type;
      if (type >= types.size())
        fail(context, "tile " + std::to_string(t) + " instance " + std::to_string(i),
             "molecule type " + std::to_string(type) + " is not among the " + std::to_string(types.size()) + " types given");
      used[type] = true;
    }
  for (std::size_t i = 0; i < types.size(); ++i) {
    const float r = types[i].bounding_radius;
    radii[i] = r;
    if (!used[i]) continue;
    double reach = 0.0;
    for (const tiles::AtomSphere& a : types[i].atoms)
      reach = std::max(reach, glm::length(glm::dvec3(a.centre)) + double(a.radius));
    if (!std::isfinite(r) || double(r) < reach - 1e-5 * (1.0 + reach))
      fail(context, "molecule type " + std::to_string(i) + " (" + types[i].name + ")",
           "bounding radius " + std::to_string(r) + " Å does not cover its atoms (" + std::to_string(reach) +
               " Å about the origin); the seam rule needs it");
  }
  return radii;
}

std::vector<glm::vec4> tile_extents(const tiles::WangSet& set) {
  std::vector<glm::vec4> extents;
  extents.reserve(set.tiles.size());
  for (const tiles::WangTile& tile : set.tiles) {
    glm::vec4 extent(INFINITY, INFINITY, -INFINITY, -INFINITY);
    for (const tiles::Instance& in : tile.instances)
      extent = glm::vec4(glm::min(glm::vec2(extent), glm::vec2(in.position)),
                         glm::max(glm::vec2(extent.z, extent.w), glm::vec2(in.position)));
    extents.push_back(extent);
  }
  return extents;
}

// Triangle t's chart and, where the chart is valid, its replication area for tiles of UV size s.
TriangleMapping map_triangle(const mesh::ProxyMesh& mesh, std::size_t t, const std::vector<glm::vec2>& snapped, float s) {
  TriangleMapping tm{};
  for (int c = 0; c < 3; ++c) {
    tm.position[c] = glm::vec3(mesh.corner_position(t, c));
    tm.normal[c] = glm::normalize(glm::vec3(mesh.corner_normal(t, c)));
    tm.uv[c] = snapped[mesh.uv_triangles[t][c]];
  }
  tm.chart = gpu::chart_make(tm.position[0], tm.position[1], tm.position[2], tm.uv[0], tm.uv[1], tm.uv[2], tm.normal[0],
                             tm.normal[1], tm.normal[2]);
  tm.valid = gpu::chart_valid(tm.chart);
  tm.uv_min = glm::min(tm.uv[0], glm::min(tm.uv[1], tm.uv[2]));
  tm.uv_max = glm::max(tm.uv[0], glm::max(tm.uv[1], tm.uv[2]));
  if (!tm.valid) return tm;  // owns nothing: no replication area, not part of W×H
  tm.origin = gpu::replication_origin(tm.uv_min, s);
  tm.extent = gpu::replication_extent(tm.uv_min, tm.uv_max, s);
  return tm;
}

// Seams on the snapped UVs (what ownership sees): an edge of exactly two faces whose faces carry
// different UVs at one of its endpoints. Both faces get the edge bit (the corner the edge starts
// from, EdgeUse.corner: from corner c to c + 1 mod 3); a face at either endpoint that holds no
// seam edge through that vertex (a fan face) gets the corner bit of that vertex (seam.h): the
// faces holding such an edge are already kept clear of the seam by their edge bits.
void mark_seams(const mesh::ProxyMesh& mesh, const std::vector<glm::vec2>& snapped, std::vector<TriangleMapping>& triangles) {
  const std::vector<mesh::MeshEdge> edges = mesh::collect_edges(mesh);
  std::vector<std::uint32_t> seam_vertices;
  for (const mesh::MeshEdge& edge : edges) {
    if (edge.uses.size() != 2) continue;
    auto uv_at = [&](const mesh::EdgeUse& use, std::uint32_t vertex) {
      const int c = mesh.triangles[use.face][use.corner] == vertex ? use.corner : (use.corner + 1) % 3;
      return snapped[mesh.uv_triangles[use.face][c]];
    };
    const mesh::EdgeUse& u0 = edge.uses[0];
    const mesh::EdgeUse& u1 = edge.uses[1];
    if (uv_at(u0, edge.a) == uv_at(u1, edge.a) && uv_at(u0, edge.b) == uv_at(u1, edge.b)) continue;
    for (const mesh::EdgeUse& use : edge.uses) triangles[use.face].seam_edges |= 1u << use.corner;
    seam_vertices.push_back(edge.a);
    seam_vertices.push_back(edge.b);
  }
  std::vector<bool> on_seam(mesh.positions.size(), false);
  for (const std::uint32_t v : seam_vertices) on_seam[v] = true;
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const std::uint32_t edge_bits = triangles[t].seam_edges;
    for (int c = 0; c < 3; ++c) {
      // Edges through corner c: edge c (c → c+1) and edge c−1 (c−1 → c).
      const bool holds_seam_here = ((edge_bits >> c) & 1u) != 0u || ((edge_bits >> ((c + 2) % 3)) & 1u) != 0u;
      if (on_seam[mesh.triangles[t][c]] && !holds_seam_here) triangles[t].seam_edges |= 1u << (3 + c);
    }
  }
}

}  // namespace

float snap_uv(double uv) {
  // Below 0.5 float can hold finer values than the grid; from 0.5 on its spacing is a multiple of it.
  if (std::abs(uv) < 0.5) return static_cast<float>(std::nearbyint(uv / kGridStep) * kGridStep);
  return static_cast<float>(uv);
}

glm::vec2 snap_uv(const glm::dvec2& uv) { return {snap_uv(uv.x), snap_uv(uv.y)}; }

MembraneMapping::MembraneMapping(const mesh::ProxyMesh& mesh, const tiles::WangSet& set,
                                 const tiles::TilingRecipe& recipe, double k,
                                 const std::vector<tiles::MoleculeType>& types, std::string context,
                                 SeamRule seam_rule, float smooth)
    : set_(&set), recipe_(&recipe), seam_rule_(seam_rule), smooth_(smooth) {
  check_inputs(mesh, set, recipe, k, context, smooth);
  s_ = static_cast<float>(set.edge / k);
  s_over_S_ = s_ / set.edge;
  if (!(s_ > 0.f) || !std::isfinite(s_) || !(s_over_S_ > 0.f))
    fail(context, "scale", "tile UV size S/k is not a positive finite float");
  snapped_uvs_ = snap_mesh_uvs(mesh, context);
  type_radius_ = type_radii(set, types, context);
  tile_extent_ = tile_extents(set);
  triangles_.reserve(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    triangles_.push_back(map_triangle(mesh, t, snapped_uvs_, s_));
    const TriangleMapping& tm = triangles_.back();
    if (tm.valid) area_ = glm::max(area_, gpu::replication_extent_bound(tm.uv_min, tm.uv_max, s_));
  }
  mark_seams(mesh, snapped_uvs_, triangles_);
}

std::size_t MembraneMapping::seam_dropped_count() const {
  std::size_t all = 0, kept = 0;
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    if (triangles_[t].seam_edges == 0) continue;
    for_each_owned_membrane_place(t, [&](const OwnedPlace&) { ++all; }, SeamRule::ignore);
    for_each_owned_membrane_place(t, [&](const OwnedPlace&) { ++kept; });
  }
  return all - kept;
}

MembraneMapping::OwnershipCorners::OwnershipCorners(const TriangleMapping& tm)
    : q{gpu::own_quantize(tm.uv[0]), gpu::own_quantize(tm.uv[1]), gpu::own_quantize(tm.uv[2])} {}

MembraneMapping::TileCover MembraneMapping::tile_cover(const OwnershipCorners& corners, glm::vec2 g,
                                                       std::uint32_t tile) const {
  const glm::vec4 extent = tile_extent_[tile];
  if (!(extent.x <= extent.z)) return TileCover::none;  // a tile without copies
  // chart_molecule_uv and own_quantize never decrease as a position grows (float rounding is
  // monotone, s/S > 0), so the quantised UVs of the tile's copies lie in this integer box.
  const glm::ivec2 lo = gpu::own_quantize(gpu::chart_molecule_uv(g, s_over_S_, glm::vec3(extent.x, extent.y, 0.f)));
  const glm::ivec2 hi = gpu::own_quantize(gpu::chart_molecule_uv(g, s_over_S_, glm::vec3(extent.z, extent.w, 0.f)));
  const std::array<glm::ivec2, 4> box = {lo, glm::ivec2(hi.x, lo.y), glm::ivec2(lo.x, hi.y), hi};
  // An edge's test (own_edge_side_q against the interior's side) holds on a half-plane, exactly:
  // if it fails at every corner of the box it fails on the whole box, and if it holds at every
  // corner it holds on the whole box.
  bool everywhere = true;
  for (int e = 0; e < 3; ++e) {
    const glm::ivec2& a = corners.q[e];
    const glm::ivec2& b = corners.q[(e + 1) % 3];
    const int inner = gpu::own_edge_inner_q(a, b, corners.q[(e + 2) % 3]);
    int inside = 0;
    for (const glm::ivec2& p : box) inside += gpu::own_edge_side_q(a, b, p) == inner;
    if (inside == 0) return TileCover::none;
    everywhere = everywhere && inside == 4;
  }
  return everywhere ? TileCover::all : TileCover::some;
}

std::uint32_t MembraneMapping::tile_at(glm::ivec2 cell) const {
  const int x = recipe_->size[0];
  const int y = recipe_->size[1];
  const int a = ((cell.x % x) + x) % x;
  const int b = ((cell.y % y) + y) % y;
  return recipe_->at(a, b);
}

}  // namespace nano::shell
