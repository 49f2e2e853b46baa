#include "bake/scene_bake/membrane_bake.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bake/mesh/uv_distortion.hpp"
#include "bake/shell/membrane_mapping.hpp"
#include "bake/shell/shell_offsets.hpp"
#include "bake/scene_bake/shell_cache.hpp"
#include "common/error.hpp"

namespace nano::scene_bake {

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

// At most this many triangles, or one in kTrianglesPerLipidHole, may leave out lipids no prism holds.
constexpr std::size_t kFewTrianglesLeavingLipids = 8;
constexpr std::size_t kTrianglesPerLipidHole = 2000;

// The triangles no prism fits even without their proteins, named with where they are.
InputError unshellable(const shell::MembraneMapping& mapping, const std::vector<std::uint32_t>& triangles) {
  std::string text = std::to_string(triangles.size()) +
                     " triangles could not be given a prism that contains their lipids (the surface folds tighter than "
                     "the bilayer can follow there):";
  const std::size_t shown = std::min<std::size_t>(triangles.size(), 5);
  for (std::size_t i = 0; i < shown; ++i) {
    const std::uint32_t t = triangles[i];
    const shell::TriangleMapping& tm = mapping.triangle(t);
    const glm::dvec3 c = (glm::dvec3(tm.position[0]) + glm::dvec3(tm.position[1]) + glm::dvec3(tm.position[2])) / 3.0;
    char line[160];
    std::snprintf(line, sizeof line, "\n  triangle %u at (%.1f, %.1f, %.1f) Å", t, c.x, c.y, c.z);
    text += line;
  }
  if (shown < triangles.size()) text += "\n  ...";
  return InputError("", "membrane", text);
}

// Tile space per Å of surface, as a float (rounded down) so that s = S / k is reproducible by the
// shader's float division; some float s have no float k at all.
// Tiles packed for what the meshes do to them (a cell's) must never be compressed where nothing
// checks them: molecules are rigid, so where the map shrinks tile space (cube-sphere corners, σ_min
// ≈ 0.76 of the mean) copies packed collision-free would overlap; the plan scales them by the
// smallest singular value of the triangles it does not check, which only spreads them. Tiles packed
// rigid are checked copy by copy on the real surface anyway: the plan gives them the mean scale, so
// that the surface holds the patch's density on average; what compression pushes together is pruned.
double tile_scale(const SurfaceChecks& checks) {
  const double target = checks.plan.tile_scale;
  if (!(target > 0)) throw InputError("", "membrane", "the mesh has no triangle with a usable UV chart");
  float k_float = static_cast<float>(target);
  if (double(k_float) > target) k_float = std::nextafter(k_float, 0.f);
  return k_float;
}

// What the shells and the pruning of one membrane read.
struct MembraneSurface {
  const SurfaceChecks& checks;
  const shell::MembraneMapping& mapping;
  const mesh::ProxyMesh& mesh;
  const std::vector<tiles::MoleculeType>& types;  // the set's
  const BakedWangSet& tiles;
  const std::vector<BakedMolecule>& library;
  int threads;
};

shell::ShellResult compute_shells(const MembraneSurface& m) {
  std::vector<bool> droppable(m.types.size(), false);
  for (const std::uint32_t t : m.tiles.protein_types) droppable.at(t) = true;
  shell::ShellResult shells = shell::compute_shell_offsets(m.mapping, m.types, m.threads, droppable);
  // A few triangles where a lipid finds no prism (a tight spot the judgement let pass) leave those
  // lipids out, counted in the report; more are a surface the bilayer cannot follow.
  const std::size_t allowed = std::max(kFewTrianglesLeavingLipids, m.mapping.triangle_count() / kTrianglesPerLipidHole);
  if (shells.lipids_left_out.size() > allowed) throw unshellable(m.mapping, shells.lipids_left_out);
  return shells;
}

// Proteins no prism could hold where they were are dropped first; per-compartment counts are settled
// next, on the whole surface and among the copies left, so a dropped spike is placed elsewhere: the
// copies dropped then take no lipid with them (the patch was laid through them), and the pruning
// removes the lipids that the kept ones displace.
shell::PrunedMembrane drops_before_pruning(const MembraneSurface& m, shell::ShellResult& shells,
                                           const PerCompartment& per_compartment, shell::PruningSettings& pruning) {
  shell::PrunedMembrane limited;
  limited.dropped = std::move(shells.dropped);
  limited.dropped_by_type.assign(shells.dropped_by_type.begin(), shells.dropped_by_type.end());
  if (per_compartment.empty()) return limited;
  std::vector<std::uint32_t> kept_on;
  for (const auto& [molecule, count] : per_compartment)
    for (std::uint32_t i = 0; i < m.tiles.molecule_of_type.size(); ++i)
      if (m.tiles.molecule_of_type[i] == molecule) shell::limit_copies(m.mapping, limited, i, count, &kept_on);
  if (!pruning.whole_surface)
    for (const std::uint32_t t : kept_on) pruning.checked_triangles[t] = 1;
  return limited;
}

shell::PrunedMembrane prune(const MembraneSurface& m, shell::ShellResult& shells, const PerCompartment& per_compartment) {
  shell::PruningSettings pruning;
  pruning.whole_surface = m.checks.whole_surface;
  if (!pruning.whole_surface) pruning.checked_triangles = m.checks.plan.checked;
  pruning.owned_copies = shells.stats.owned_molecules;  // the same mapping, the same ownership
  const shell::PrunedMembrane limited = drops_before_pruning(m, shells, per_compartment, pruning);
  if (shells.stats.unfit_triangles > 0 || !per_compartment.empty()) pruning.dropped_before = limited.dropped;
  shell::PrunedMembrane pruned = shell::prune_membrane(m.mapping, m.mesh, m.types, pruning, m.threads);
  for (std::size_t i = 0; i < m.types.size(); ++i) pruned.dropped_by_type[i] += limited.dropped_by_type[i];
  return pruned;
}

// Per library molecule: copies kept, dropped, alternates shown and proteins no prism held.
void count_by_molecule(const MembraneSurface& m, const ShellStage& stage, BakedMembrane& baked) {
  const std::vector<std::uint32_t>& molecule_of_type = m.tiles.molecule_of_type;
  baked.unfit_by_molecule.assign(m.library.size(), 0);
  baked.copies_by_molecule.assign(m.library.size(), 0);
  baked.dropped_by_molecule.assign(m.library.size(), 0);
  baked.alternates_by_molecule.assign(m.library.size(), 0);
  for (std::size_t i = 0; i < m.types.size(); ++i) {
    baked.unfit_by_molecule[molecule_of_type[i]] += stage.unfit_by_type[i];
    baked.copies_by_molecule[molecule_of_type[i]] +=
        stage.owned_by_type[i] - baked.pruning.dropped_by_type[i] + baked.pruning.alternates_by_type[i];
    baked.dropped_by_molecule[molecule_of_type[i]] += baked.pruning.dropped_by_type[i];
    baked.alternates_by_molecule[molecule_of_type[i]] += baked.pruning.alternates_by_type[i];
  }
}

void store_shells(const shell::MembraneMapping& mapping, const ShellStage& stage, BakedMembrane& baked) {
  baked.shells.resize(mapping.triangle_count());
  baked.reach = stage.reach;
  for (std::size_t t = 0; t < mapping.triangle_count(); ++t) {
    const shell::TriangleMapping& tm = mapping.triangle(t);
    gpu::TriangleShell& s = baked.shells[t];
    s.uv_min_max = glm::vec4(tm.uv_min, tm.uv_max);
    s.h_plus = stage.offsets[t].h_plus;
    s.h_minus = stage.offsets[t].h_minus;
    s.side_offset = stage.offsets[t].side;
    s.seam_edges = mapping.seam_edges(t);
    baked.inner_height = std::max(baked.inner_height, double(s.h_minus));
  }
  const glm::ivec2 area = mapping.replication_area();
  baked.replication_width = static_cast<std::uint32_t>(area.x);
  baked.replication_height = static_cast<std::uint32_t>(area.y);
}


// Everything compute_shells and prune read, in bytes: the snapped mesh, the set as the mapping
// reads it (tiles, types, recipe, scale, surface shape), what the pruning checks and keeps, and the
// baker itself. Field by field, never a struct's padding.
ShellStageKey shell_stage_key(const MembraneSurface& m, const tiles::TilingRecipe& recipe, double k, float smooth,
                              const PerCompartment& per_compartment) {
  ShellStageKey key;
  key.add(baker_build_hash());
  const mesh::ProxyMesh& mesh = m.mesh;
  key.add_all(mesh.positions), key.add_all(mesh.triangles), key.add_all(mesh.uvs), key.add_all(mesh.uv_triangles);
  key.add_all(mesh.normals), key.add_all(mesh.normal_triangles);
  key.add(k), key.add(smooth), key.add(recipe.dims), key.add(recipe.size), key.add(recipe.periodic), key.add_all(recipe.cells);
  key.add(m.tiles.set.dims), key.add(m.tiles.set.edge), key.add(std::uint64_t(m.tiles.set.tiles.size()));
  for (const tiles::WangTile& tile : m.tiles.set.tiles) key.add_instances(tile.instances);
  key.add_types(m.types);
  key.add_all(m.tiles.protein_types);
  key.add(m.checks.whole_surface), key.add(m.checks.plan.tile_scale), key.add_all(m.checks.plan.checked);
  // Counts per compartment by the set's types they limit (library indices differ between scenes).
  for (const auto& [molecule, count] : per_compartment) {
    key.add(count);
    for (std::uint32_t i = 0; i < m.tiles.molecule_of_type.size(); ++i) key.add(m.tiles.molecule_of_type[i] == molecule);
  }
  return key;
}

ShellStage compute_shell_stage(const MembraneSurface& m, const PerCompartment& per_compartment) {
  shell::ShellResult shells = compute_shells(m);
  ShellStage stage;
  stage.pruning = prune(m, shells, per_compartment);
  stage.offsets = std::move(shells.offsets);
  stage.reach = std::move(shells.reach);
  stage.owned_by_type.assign(shells.owned_by_type.begin(), shells.owned_by_type.end());
  stage.unfit_by_type.assign(shells.dropped_by_type.begin(), shells.dropped_by_type.end());
  return stage;
}

// The stage from the cache when it holds this key's, else computed (and kept when there is a cache).
ShellStage shell_stage(const MembraneSurface& m, const tiles::TilingRecipe& recipe, double k, float smooth,
                       const PerCompartment& per_compartment, const std::optional<std::filesystem::path>& cache,
                       bool& from_cache) {
  from_cache = false;
  if (!cache || baker_build_hash() == 0) return compute_shell_stage(m, per_compartment);
  const ShellStageKey key = shell_stage_key(m, recipe, k, smooth, per_compartment);
  if (std::optional<ShellStage> kept = load_shell_stage(*cache, key, m.mapping.triangle_count(), m.types.size())) {
    from_cache = true;
    return std::move(*kept);
  }
  ShellStage stage = compute_shell_stage(m, per_compartment);
  store_shell_stage(*cache, key, stage);
  return stage;
}
}  // namespace

BakedMembrane bake_membrane(mesh::ProxyMesh& mesh, const BakedWangSet& tiles, const SurfaceChecks& checks,
                            const std::vector<BakedMolecule>& library, std::uint64_t seed, int threads,
                            const PerCompartment& per_compartment, const std::optional<std::filesystem::path>& cache) {
  BakedMembrane baked;
  const double k = tile_scale(checks);
  baked.tile_size = tiles.set.edge;
  baked.recipe = membrane_recipe(tiles.set, tiles.set.edge / k, seed);
  std::vector<tiles::MoleculeType> types;
  for (const std::uint32_t m : tiles.molecule_of_type) types.push_back(to_tile_molecule(library[m]));
  // Copies that clash across seams (and wherever the surface distorts the tiles) are found and
  // dropped by the pruning, so no seam band is emptied.
  baked.smooth = kMembraneSurfaceSmoothness;
  const shell::MembraneMapping mapping(mesh, tiles.set, baked.recipe, k, types, "membrane", shell::SeamRule::ignore,
                                       baked.smooth);
  baked.uv_scale = stored_uv_scale(tiles.set.edge, mapping.tile_uv_size());
  // The package stores the UVs ownership was decided on.
  const std::vector<glm::vec2>& snapped = mapping.snapped_uvs();
  for (std::size_t i = 0; i < mesh.uvs.size(); ++i) mesh.uvs[i] = glm::dvec2(snapped[i]);

  const MembraneSurface surface{checks, mapping, mesh, types, tiles, library, threads};
  ShellStage stage = shell_stage(surface, baked.recipe, k, baked.smooth, per_compartment, cache, baked.shells_from_cache);
  baked.pruning = std::move(stage.pruning);
  baked.dropped = std::move(baked.pruning.dropped);
  count_by_molecule(surface, stage, baked);
  store_shells(mapping, stage, baked);
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

}  // namespace nano::scene_bake
