#pragma once
// The membrane mapping of one compartment (ALGORITHMS.md §1): the proxy mesh's UV chart tiled with a
// Wang square set through a 2D recipe. Per triangle: its chart (tile_mapper.h) on snapped UVs, its
// replication origin and extent; for the compartment the replication area W×H. The enumerator
// for_each_owned_membrane_molecule is the explicit-instancing definition of the membrane — the same
// loop over the shared-header functions that the shader runs — so the export oracle, the shell
// offsets and the renderer all agree on which molecule belongs to which triangle and where it is.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bake/mesh/proxy_mesh.hpp"
#include "bake/tiles/molecule_type.hpp"
#include "bake/tiles/tiling_recipe.hpp"
#include "bake/tiles/wang_set.hpp"
#include "shared/ownership.h"
#include "shared/render_membrane_filter.h"
#include "shared/seam.h"
#include "shared/tile_mapper.h"

namespace nano::shell {

// UV snapped to a multiple of 2^-24 (the ownership grid, ownership.h) and stored as float: below 0.5
// in magnitude it is rounded to the nearest multiple of 2^-24 (|Δ| ≤ 2^-25, exact in float); from
// 0.5 on every float is already such a multiple, so it is the nearest float (|Δ| ≤ half an ulp, i.e.
// ≤ 2^-25 below 1 and ≤ 2^-21 below 16). Then own_quantize sees exactly the stored chart.
float snap_uv(double uv);
glm::vec2 snap_uv(const glm::dvec2& uv);

struct TriangleMapping {
  std::array<glm::vec3, 3> position;  // compartment space, Å
  std::array<glm::vec3, 3> normal;    // unit corner normals
  std::array<glm::vec2, 3> uv;        // snapped
  gpu::TriangleChart chart;           // chart_make of the above
  bool valid = false;                 // chart_valid: an unusable triangle owns nothing
  glm::vec2 uv_min{0.f}, uv_max{0.f};
  glm::ivec2 origin{0};               // replication_origin
  glm::ivec2 extent{0};               // replication_extent: the tiles this triangle walks
  std::uint32_t seam_edges = 0;       // TriangleShell.seam_edges (shared/seam.h): bits 0-2 edge
                                      // (k, k+1 mod 3) is a UV seam; bits 3-5 corner k is on a seam
};

// Whether the enumerator applies the seam rule (shared/seam.h). `ignore` yields the plain
// ownership partition (every molecule of the chart exactly once).
enum class SeamRule { apply, ignore };

// Which instances of a tile the enumerator yields: all, or only the set's own copies or only its
// alternates (tiles::Instance::alternate), told apart before any ownership test.
enum class Instances { all, originals, alternates };

// One membrane molecule as ownership sees it: which copy, and the UV point that decided.
struct OwnedPlace {
  glm::ivec2 cell{0};         // UV tile cell (a, b), not wrapped; its tile origin is g = cell·s
  std::uint32_t tile = 0;     // index into the Wang set: recipe.at(a mod X, b mod Y)
  std::uint32_t instance = 0; // index into that tile's instances
  std::uint32_t type = 0;     // molecule type of the instance
  glm::vec2 uv{0.f};          // uv_m, the point ownership decided on
};

// One membrane molecule as the triangle that owns it sees it.
struct OwnedMolecule : OwnedPlace {
  gpu::Affine3 transform;     // compartment space (chart_membrane_molecule)
};

class MembraneMapping {
public:
  // `mesh` in compartment space with per-corner UVs and unit normals; `set` a Wang square set
  // (dims 2) and `recipe` a 2D recipe over it; k = global scale (Å per UV unit), so the tile UV size
  // is s = set.edge / k. The mapping keeps references to `set` and `recipe` (they must outlive it);
  // the mesh is copied into per-triangle data. Throws InputError(context, ...) for a mesh without UVs
  // or normals, a UV that is not finite or has |uv| ≥ 16, a non-positive or non-finite k or edge, a
  // recipe that is not 2D or names a missing tile, or a non-finite tile UV size.
  // `types`: the molecule types the set's instances index. Their bounding_radius (the package's
  // MoleculeType.aabb_min.w) is the seam rule's radius; it must cover the atoms about the origin
  // (InputError otherwise, e.g. for a type whose radius was left 0). Seams: the edges of the mesh
  // (by position index) shared by exactly two triangles that carry different snapped UVs at an
  // endpoint; both triangles get the edge bit and every triangle at the seam edge's endpoints gets
  // the corner bit (seam.h).
  // `seam_rule`: whether the package this mapping bakes applies the seam rule (format 2.0-2.1
  // packages did); ignore when the copies that really clash across seams are dropped instead
  // (membrane_pruning.hpp). The seams themselves are found either way (TriangleMapping.seam_edges).
  // `smooth`: the shape factor of the surface copies stand on (chart_smooth_position; 0 = flat facets),
  // in [0, 1]; the package stores it as Compartment.scales.w.
  MembraneMapping(const mesh::ProxyMesh& mesh, const tiles::WangSet& set, const tiles::TilingRecipe& recipe,
                  double k, const std::vector<tiles::MoleculeType>& types, std::string context = "membrane",
                  SeamRule seam_rule = SeamRule::apply, float smooth = 0.f);

  std::size_t triangle_count() const { return triangles_.size(); }
  const TriangleMapping& triangle(std::size_t t) const { return triangles_[t]; }
  const std::vector<glm::vec2>& snapped_uvs() const { return snapped_uvs_; }
  const tiles::WangSet& set() const { return *set_; }

  float tile_edge() const { return set_->edge; }  // S, Å
  float tile_uv_size() const { return s_; }       // s = S/k rounded to float: the value to store
  float s_over_S() const { return s_over_S_; }    // s/S in float, as the shader forms it
  float smooth() const { return smooth_; }        // shape factor of the surface (chart_smooth_position)
  // W×H: the maximum of replication_extent_bound over the valid triangles.
  glm::ivec2 replication_area() const { return area_; }

  // Seam rule input: the radius of each type (bounding_radius).
  float type_radius(std::uint32_t type) const { return type_radius_[type]; }
  // The seam bits the package stores: the seams' bits, or none when the seam rule is not applied.
  std::uint32_t seam_edges(std::size_t t) const { return seam_rule_ == SeamRule::apply ? triangles_[t].seam_edges : 0u; }
  // The number of (triangle, owned molecule) pairs the seam rule drops, over the whole mesh.
  std::size_t seam_dropped_count() const;

  // Tile of UV cell (a, b): recipe.at(a mod X, b mod Y) with a non-negative modulo, so a recipe
  // smaller than the chart repeats.
  std::uint32_t tile_at(glm::ivec2 cell) const;

  // Calls f(const OwnedMolecule&) for every molecule of the replication area of triangle t that t
  // owns (own_triangle_owns on its snapped UVs) and, with SeamRule::apply, the seam rule keeps
  // (seam_drops of shared/seam.h on the molecule's surface point), in slot order (v outer, u inner), then
  // instance order. Walks the triangle's own extent: slots of W×H beyond it hold no molecule inside
  // the triangle's UV box (replication slack), which the tests check.
  template <class F>
  void for_each_owned_membrane_molecule(std::size_t t, F&& f, SeamRule rule = SeamRule::apply) const {
    for_each_owned_membrane_place(t, [&](const OwnedPlace& place) {
      OwnedMolecule m;
      static_cast<OwnedPlace&>(m) = place;
      m.transform = transform_of(t, place);
      f(static_cast<const OwnedMolecule&>(m));
    }, rule);
  }

  // The same molecules in the same order as f(const OwnedPlace&), not yet placed: callers that keep
  // only some of them, or need only their centres, place those with transform_of or centre_of.
  // A tile whose copies the triangle owns all or none of (tile_cover, exact) skips the per-copy
  // ownership test: most tiles of a large triangle lie wholly inside or outside it.
  template <class F>
  void for_each_owned_membrane_place(std::size_t t, F&& f, SeamRule rule = SeamRule::apply,
                                     Instances which = Instances::all) const {
    const TriangleMapping& tm = triangles_[t];
    if (!tm.valid) return;
    const OwnershipCorners corners(tm);
    if (corners.degenerate()) return;  // own_triangle_owns is false everywhere
    for (int j = 0; j < tm.extent.y; ++j)
      for (int i = 0; i < tm.extent.x; ++i) {
        OwnedPlace place;
        place.cell = gpu::replication_tile_index(tm.origin, glm::ivec2(i, j));
        const glm::vec2 g = gpu::replication_tile_uv(place.cell, s_);
        place.tile = tile_at(place.cell);
        const TileCover cover = tile_cover(corners, g, place.tile);
        if (cover == TileCover::none) continue;
        const std::vector<tiles::Instance>& instances = set_->tiles[place.tile].instances;
        for (std::size_t k = 0; k < instances.size(); ++k) {
          const tiles::Instance& in = instances[k];
          if (which != Instances::all && in.alternate != (which == Instances::alternates)) continue;
          // chart_membrane_molecule's uv_m: the point ownership and the seam rule decide on.
          place.uv = gpu::chart_molecule_uv(g, s_over_S_, in.position);
          if (cover == TileCover::some && !corners.owns(place.uv)) continue;
          if (rule == SeamRule::apply && seam_rule_ == SeamRule::apply &&
              gpu::seam_drops(tm.seam_edges, tm.position[0], tm.position[1], tm.position[2],
                              gpu::chart_position(tm.chart, place.uv), type_radius_[in.type]))
            continue;
          place.instance = static_cast<std::uint32_t>(k);
          place.type = in.type;
          f(static_cast<const OwnedPlace&>(place));
        }
      }
  }

  // The key triangle t's drop list knows the copy by: membrane_copy_key(its slot in t's replication
  // area, its instance), as the shader looks it up.
  std::uint32_t copy_key(std::size_t t, const OwnedPlace& place) const {
    const glm::ivec2 slot = place.cell - triangles_[t].origin;
    return gpu::membrane_copy_key(static_cast<std::uint32_t>(slot.x) + static_cast<std::uint32_t>(area_.x) *
                                                                           static_cast<std::uint32_t>(slot.y),
                                  place.instance);
  }
  // Compartment-space transform of a copy triangle t owns (chart_membrane_molecule).
  gpu::Affine3 transform_of(std::size_t t, const OwnedPlace& place) const {
    const tiles::Instance& in = set_->tiles[place.tile].instances[place.instance];
    const glm::vec4 q(in.rotation.x, in.rotation.y, in.rotation.z, in.rotation.w);  // glm quat is (w,x,y,z)
    glm::vec2 uv;
    return gpu::chart_membrane_molecule(triangles_[t].chart, gpu::replication_tile_uv(place.cell, s_), s_over_S_,
                                        smooth_, in.position, q, uv);
  }
  // Its translation alone, bit for bit (chart_membrane_centre, the translation chart_membrane_molecule
  // computes), without the frame (an atan, a sine and a cosine per copy): the shell offsets need only centres.
  glm::vec3 centre_of(std::size_t t, const OwnedPlace& place) const {
    const gpu::TriangleChart& chart = triangles_[t].chart;
    const float z = set_->tiles[place.tile].instances[place.instance].position.z;
    return gpu::chart_membrane_centre(chart, place.uv, smooth_, z, gpu::chart_normal(chart, place.uv));
  }

private:
  // own_triangle_owns of one triangle with its corners quantised once, not per molecule.
  struct OwnershipCorners {
    explicit OwnershipCorners(const TriangleMapping& tm);
    bool degenerate() const { return gpu::own_edge_inner_q(q[0], q[1], q[2]) == 0; }
    bool owns(glm::vec2 uv) const { return gpu::own_triangle_owns_q(q[0], q[1], q[2], gpu::own_quantize(uv)); }
    std::array<glm::ivec2, 3> q;
  };
  // Which of a tile's copies the triangle can own, decided on the box of their quantised UVs.
  enum class TileCover { none, some, all };
  TileCover tile_cover(const OwnershipCorners& corners, glm::vec2 g, std::uint32_t tile) const;

  const tiles::WangSet* set_;
  const tiles::TilingRecipe* recipe_;
  SeamRule seam_rule_ = SeamRule::apply;
  float s_ = 0.f;
  float s_over_S_ = 0.f;
  float smooth_ = 0.f;
  glm::ivec2 area_{0};
  std::vector<float> type_radius_;
  std::vector<glm::vec4> tile_extent_;  // per Wang tile: min x, min y, max x, max y of its copies
  std::vector<glm::vec2> snapped_uvs_;
  std::vector<TriangleMapping> triangles_;
};

}  // namespace nano::shell
