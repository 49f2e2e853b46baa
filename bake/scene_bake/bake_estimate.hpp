#pragma once
// What a bake will take, estimated from the scene, its molecules and its meshes before the heavy
// stages (tile sets, shells, core grids, package): the copies each compartment will hold, the work
// of each stage and from it time and peak memory. `nanobake bake --dry-run` prints it; the baker
// refuses a bake whose peak memory would pass --max-memory. The per-stage cost coefficients are
// fitted on the bundled scenes (docs/bake-estimate.md) on a 2-core machine; tests check the
// estimate within 2x of what the bundled bakes then take.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bake/scene/scene_description.hpp"
#include "bake/scene/scene_feasibility.hpp"
#include "bake/scene_bake/molecule_library.hpp"

namespace nano::scene_bake {

struct CompartmentEstimate {
  std::string name;
  double area_um2 = 0.0, volume_um3 = 0.0;
  std::vector<std::pair<std::string, double>> copies;  // molecule (or lipid species) name -> copies in one compartment
};

struct StageEstimate {
  std::string stage;  // as the bake names it ("tile sets", "shells", ...)
  double work = 0.0;  // the stage's own measure of work (atoms of copies placed or checked)
  double cpu_seconds = 0.0;
};

// One part of the peak memory, with what a scene changes to shrink it.
struct MemoryTerm {
  std::string what;
  double bytes = 0.0;
  std::string advice;
};

struct BakeEstimate {
  std::vector<CompartmentEstimate> compartments;
  std::uint64_t instances = 0;
  double represented_atoms = 0.0;  // the whole scene
  std::vector<StageEstimate> stages;
  double cpu_seconds = 0.0;   // all stages after the meshes
  double wall_seconds = 0.0;  // with the bake's worker threads
  int jobs = 1;
  double peak_bytes = 0.0;    // resident memory at the bake's peak: the sum of `memory`
  std::vector<MemoryTerm> memory;
};

// A compartment's mesh at its final size, and what the checks found of it.
struct EstimatedMesh {
  scene::CompartmentMeasure measure;  // with the bilayer thickness of its membrane (0: none)
  double seam_length = 0.0;           // Å of UV seams: where a large membrane is checked copy by copy
  double checked_share = 1.0;         // of its area, the triangles whose copies are all checked (membrane_surface.hpp)
  bool shells_cached = false;         // its shells stage comes from the bake cache: nothing checked, no memory for it
};

// The copies a membrane puts on `area` Å² at the requested densities (a lipid patch at its own),
// by which the baker chooses to check every copy on the surface or those along seams only.
double membrane_copies_for_pruning(double area, const scene::MembraneDescription& membrane,
                                   const std::optional<BakedLipidPatch>& patch);

// One EstimatedMesh per compartment; `patches[m]` is membrane m's lipid patch.
// `sets_cached`: per membrane, then per soluble, whether its tile set came from the bake cache (it
// then costs no packing); empty: none did.
BakeEstimate estimate_bake(const scene::SceneDescription& scene, const std::vector<BakedMolecule>& library,
                           const std::vector<std::optional<BakedLipidPatch>>& patches,
                           const std::vector<EstimatedMesh>& meshes, int jobs, const std::vector<bool>& sets_cached = {});

// The estimate as the lines `--dry-run` prints.
std::string describe(const BakeEstimate& estimate);

// Why a bake is refused under --max-memory: the estimate, the limit, and what to change (the
// largest parts of the memory first).
std::string over_memory_budget(const BakeEstimate& estimate, double max_bytes);

// Bytes in "24G", "512M", "1.5GB", "2000000": K, M, G, T powers of 1024; nullopt if unreadable.
std::optional<double> parse_byte_size(const std::string& text);

// What this machine has: MemAvailable, else physical memory (bytes); 0 when unknown.
double available_memory_bytes();

// This process so far: CPU seconds (user + system, all threads) and its peak resident memory.
double process_cpu_seconds();
double peak_resident_bytes();

}  // namespace nano::scene_bake
