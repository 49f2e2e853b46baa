#pragma once
// A compartment's shell space: the membrane's tiles mapped through the mesh's UV chart, the
// adaptive prism of every triangle, and how many copies that represents.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "bake/mesh/proxy_mesh.hpp"
#include "bake/scene_bake/membrane_surface.hpp"
#include "bake/scene_bake/molecule_library.hpp"
#include "bake/scene_bake/wang_bake.hpp"
#include "bake/shell/membrane_pruning.hpp"
#include "shared/package_records.h"

namespace nano::scene_bake {

// Shape factor of the smooth surface membrane copies stand on (chart_smooth_position; stored as
// Compartment.scales.w). Flat facets tilt copies against each other by up to half the dihedral angle
// (a red blood cell's rim: 3.7°), which its tiles must be packed for. With 1/2, a sphere's facets are
// lifted onto the sphere to second order and their normals match the interpolated ones (0.0004 rad
// off where flat facets of 0.08 rad are 0.08 off); Phong's usual 3/4 overshoots by half the sag.
inline constexpr float kMembraneSurfaceSmoothness = 0.5f;

struct BakedMembrane {
  tiles::TilingRecipe recipe;
  double uv_scale = 0.0;   // k, Å of surface per UV unit
  float smooth = 0.f;      // shape factor of the surface copies stand on (Compartment.scales.w)
  double tile_size = 0.0;  // S, Å
  std::uint32_t replication_width = 0, replication_height = 0;
  std::vector<gpu::TriangleShell> shells;         // one per mesh triangle
  std::vector<float> reach;                       // per mesh triangle: shell::ShellResult::reach
  std::vector<std::vector<std::uint32_t>> dropped;  // per mesh triangle: keys of the copies it drops and alternates it shows
  std::vector<std::uint64_t> copies_by_molecule;  // kept copies, indexed like the molecule library
  std::vector<std::uint64_t> dropped_by_molecule;  // copies dropped because they clash on the surface
  std::vector<std::uint64_t> alternates_by_molecule;  // alternates shown in place of dropped copies
  std::vector<std::uint64_t> unfit_by_molecule;  // proteins left out where no prism could hold them (counted in dropped too)
  double inner_height = 0.0;                      // largest h₋: how deep the shell reaches
  shell::PrunedMembrane pruning;                  // what the clash pruning looked at (dropped moved out)
  bool shells_from_cache = false;                 // the shells stage read from the bake cache (shell_cache.hpp)
};

// The float UV scale k stored in the package: float(S) / k == s exactly, as the renderer computes it.
float stored_uv_scale(float tile_size, float tile_uv_size);

// (library molecule, copies) the compartment keeps of a protein at most (scene `per_compartment`).
using PerCompartment = std::vector<std::pair<std::uint32_t, std::uint64_t>>;

// Which copies of the membrane on this mesh are checked where they stand (membrane_surface.hpp).
struct SurfaceChecks {
  const MeshSurfacePlan& plan;  // the tile scale, and the triangles checked copy by copy
  bool whole_surface = true;    // every copy (tiles packed rigid)
};

// Snaps the mesh's UVs in place (the ownership contract) and computes everything above. On a
// membrane not checked everywhere, the triangles holding what `per_compartment` keeps are checked
// too (those proteins stand in the lipid patch, laid through them). With a `cache` directory the
// shells and the pruning are read from it when it holds them for these very inputs, and kept there
// otherwise (shell_cache.hpp).
BakedMembrane bake_membrane(mesh::ProxyMesh& mesh, const BakedWangSet& tiles, const SurfaceChecks& checks,
                            const std::vector<BakedMolecule>& library, std::uint64_t seed, int threads,
                            const PerCompartment& per_compartment = {},
                            const std::optional<std::filesystem::path>& cache = std::nullopt);

// Shells of a compartment without a membrane: flat prisms of zero height, so the core renderer
// still has the mesh's front/back intervals and no membrane copy is ever looked for.
std::vector<gpu::TriangleShell> empty_shells(const mesh::ProxyMesh& mesh);

}  // namespace nano::scene_bake
