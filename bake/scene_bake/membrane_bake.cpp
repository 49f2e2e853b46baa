#include "bake/scene_bake/membrane_bake.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bake/mesh/uv_distortion.hpp"
#include "bake/shell/membrane_mapping.hpp"
#include "bake/shell/shell_offsets.hpp"
#include "common/error.hpp"

namespace nano::bake {

float stored_uv_scale(float tile_size, float tile_uv_size) {
  // The renderer derives s = S / k in float; pick the float k for which that gives exactly the s
  // the bake placed molecules with, so oracle and shader walk identical tile origins.
  // Division is monotone in k, so walk float neighbours towards the target; some quotients are
  // unreachable (the map k -> S / k skips floats), then search a small window around it.
  float k = tile_size / tile_uv_size;
  for (int step = 0; step < 64 && tile_size / k != tile_uv_size; ++step)
    k = std::nextafter(k, tile_size / k > tile_uv_size ? INFINITY : 0.f);
  if (tile_size / k != tile_uv_size) {
    float probe = tile_size / tile_uv_size;
    for (int i = 0; i < 4096 && tile_size / probe != tile_uv_size; ++i) probe = std::nextafter(probe, 0.f);
    if (tile_size / probe == tile_uv_size) k = probe;
  }
  if (tile_size / k != tile_uv_size)
    throw InputError("", "membrane", "no float UV scale reproduces the tile UV size " + std::to_string(tile_uv_size));
  return k;
}

namespace {

// The triangles no prism fits even without their proteins, named with where they are.
InputError unshellable(const shell::MembraneMapping& mapping, const shell::ShellResult& shells) {
  std::string text = std::to_string(shells.uncontained.size()) +
                     " triangles could not be given a prism that contains their lipids (the surface folds tighter than "
                     "the bilayer can follow there):";
  const std::size_t shown = std::min<std::size_t>(shells.uncontained.size(), 5);
  for (std::size_t i = 0; i < shown; ++i) {
    const std::uint32_t t = shells.uncontained[i];
    const shell::TriangleMapping& tm = mapping.triangle(t);
    const glm::dvec3 c = (glm::dvec3(tm.position[0]) + glm::dvec3(tm.position[1]) + glm::dvec3(tm.position[2])) / 3.0;
    char line[160];
    std::snprintf(line, sizeof line, "\n  triangle %u at (%.1f, %.1f, %.1f) Å", t, c.x, c.y, c.z);
    text += line;
  }
  if (shown < shells.uncontained.size()) text += "\n  ...";
  return InputError("", "membrane", text);
}

}  // namespace

BakedMembrane bake_membrane(mesh::ProxyMesh& mesh, const BakedWangSet& tiles, const std::vector<BakedMolecule>& library,
                            std::uint64_t seed, int threads,
                            const std::vector<std::pair<std::uint32_t, std::uint64_t>>& per_compartment) {
  BakedMembrane baked;
  // Tile space per Å of surface. Tiles packed for what the meshes do to them (a cell's) must never be
  // compressed: molecules are rigid, so where the map shrinks tile space (cube-sphere corners, σ_min
  // ≈ 0.76 of the mean) copies packed collision-free would overlap; scaling by the smallest singular
  // value only spreads them, which costs density wherever σ is larger (a sphere: 1/1.26 on average).
  // Tiles packed rigid are checked copy by copy on the real surface anyway: they take the mean scale,
  // so that the surface holds the patch's density on average; what compression pushes together is
  // pruned.
  const double target = tiles.packed_rigid ? mesh::uv_scale(mesh) : mesh::smallest_stretch(mesh);
  if (!(target > 0)) throw InputError("", "membrane", "the mesh has no triangle with a usable UV chart");
  // A float k (rounded down) makes s = S / k reproducible by the shader's float division; some float s
  // have no float k at all.
  float k_float = static_cast<float>(target);
  if (double(k_float) > target) k_float = std::nextafter(k_float, 0.f);
  const double k = k_float;
  baked.tile_size = tiles.set.edge;
  baked.recipe = membrane_recipe(tiles.set, tiles.set.edge / k, seed);
  std::vector<tiles::MoleculeType> types;
  for (const std::uint32_t m : tiles.molecule_of_type) types.push_back(to_tile_molecule(library[m]));
  // Copies that clash across seams (and wherever the surface distorts the tiles) are found and
  // dropped by the pruning below, so no seam band is emptied.
  baked.smooth = kMembraneSurfaceSmoothness;
  const shell::MembraneMapping mapping(mesh, tiles.set, baked.recipe, k, types, "membrane", shell::SeamRule::ignore,
                                       baked.smooth);
  baked.uv_scale = stored_uv_scale(tiles.set.edge, mapping.tile_uv_size());
  // The package stores the UVs ownership was decided on.
  const std::vector<glm::vec2>& snapped = mapping.snapped_uvs();
  for (std::size_t i = 0; i < mesh.uvs.size(); ++i) mesh.uvs[i] = glm::dvec2(snapped[i]);

  std::vector<bool> droppable(types.size(), false);
  for (const std::uint32_t t : tiles.protein_types) droppable.at(t) = true;
  shell::ShellResult shells = shell::compute_shell_offsets(mapping, types, threads, droppable);
  if (shells.stats.uncontained_triangles > 0) throw unshellable(mapping, shells);

  shell::PruningSettings pruning;
  pruning.flat_clearance = tiles.flat_clearance;
  pruning.whole_surface = tiles.packed_rigid;
  pruning.owned_copies = shells.stats.owned_molecules;  // the same mapping, the same ownership
  pruning.always_tested = tiles.laid_through;
  // Proteins no prism could hold where they were are dropped first; per-compartment counts are settled
  // next, on the whole surface and among the copies left, so a dropped spike is placed elsewhere: the
  // copies dropped then take no lipid with them (the patch was laid through them), and the pruning
  // below removes the lipids that the kept ones displace.
  shell::PrunedMembrane limited;
  limited.dropped = std::move(shells.dropped);
  limited.dropped_by_type.assign(shells.dropped_by_type.begin(), shells.dropped_by_type.end());
  baked.unfit_by_molecule.assign(library.size(), 0);
  for (std::size_t i = 0; i < types.size(); ++i) baked.unfit_by_molecule[tiles.molecule_of_type[i]] += shells.dropped_by_type[i];
  if (!per_compartment.empty()) {
    if (!tiles.packed_rigid && shells.stats.owned_molecules > pruning.whole_surface_budget)
      throw InputError("", "membrane", library[per_compartment.front().first].name +
                                           ": a per-compartment count needs a membrane checked everywhere (at most " +
                                           std::to_string(pruning.whole_surface_budget) + " copies)");
    for (const auto& [molecule, count] : per_compartment)
      for (std::uint32_t i = 0; i < tiles.molecule_of_type.size(); ++i)
        if (tiles.molecule_of_type[i] == molecule) shell::limit_copies(mapping, limited, i, count);
  }
  if (shells.stats.unfit_triangles > 0 || !per_compartment.empty()) pruning.dropped_before = limited.dropped;
  baked.pruning = shell::prune_membrane(mapping, mesh, types, pruning, threads);
  for (std::size_t i = 0; i < types.size(); ++i) baked.pruning.dropped_by_type[i] += limited.dropped_by_type[i];
  baked.dropped = std::move(baked.pruning.dropped);
  baked.copies_by_molecule.assign(library.size(), 0);
  baked.dropped_by_molecule.assign(library.size(), 0);
  baked.alternates_by_molecule.assign(library.size(), 0);
  for (std::size_t i = 0; i < types.size(); ++i) {
    baked.copies_by_molecule[tiles.molecule_of_type[i]] +=
        shells.owned_by_type[i] - baked.pruning.dropped_by_type[i] + baked.pruning.alternates_by_type[i];
    baked.dropped_by_molecule[tiles.molecule_of_type[i]] += baked.pruning.dropped_by_type[i];
    baked.alternates_by_molecule[tiles.molecule_of_type[i]] += baked.pruning.alternates_by_type[i];
  }
  baked.shells.resize(mapping.triangle_count());
  for (std::size_t t = 0; t < mapping.triangle_count(); ++t) {
    const shell::TriangleMapping& tm = mapping.triangle(t);
    gpu::TriangleShell& s = baked.shells[t];
    s.uv_min_max = glm::vec4(tm.uv_min, tm.uv_max);
    s.h_plus = shells.offsets[t].h_plus;
    s.h_minus = shells.offsets[t].h_minus;
    s.side_offset = shells.offsets[t].side;
    s.seam_edges = mapping.seam_edges(t);
    baked.inner_height = std::max(baked.inner_height, double(s.h_minus));
  }
  const glm::ivec2 area = mapping.replication_area();
  baked.replication_width = static_cast<std::uint32_t>(area.x);
  baked.replication_height = static_cast<std::uint32_t>(area.y);
  return baked;
}

std::vector<gpu::TriangleShell> empty_shells(const mesh::ProxyMesh& mesh) {
  std::vector<gpu::TriangleShell> shells(mesh.triangles.size());
  if (!mesh.has_uvs()) return shells;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    glm::dvec2 lo = mesh.corner_uv(t, 0), hi = lo;
    for (int c = 1; c < 3; ++c) {
      lo = glm::min(lo, mesh.corner_uv(t, c));
      hi = glm::max(hi, mesh.corner_uv(t, c));
    }
    shells[t].uv_min_max = glm::vec4(glm::vec2(lo), glm::vec2(hi));
  }
  return shells;
}

}  // namespace nano::bake
