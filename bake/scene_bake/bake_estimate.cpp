#include "bake/scene_bake/bake_estimate.hpp"

#include "bake/grid/exclusion_field.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <sys/resource.h>
#include <unistd.h>

#include "bake/scene/random_placement.hpp"
#include "bake/scene_bake/named_totals.hpp"
#include "bake/shell/membrane_pruning.hpp"
#include "bake/tiles/wang_sets.hpp"

namespace nano::scene_bake {
namespace {

constexpr double kA2PerUm2 = 1e8;
constexpr double kA3PerUm3 = 1e12;

// Cost coefficients, CPU seconds per unit of each stage's work and bytes per unit of memory,
// fitted on the bundled scenes' reports (stages_cpu, stages_peak_memory_bytes) on a 2-core machine:
// virion, rod cell, red blood cell and blood come within 0.7-1.3x of both (docs/bake-estimate.md).
struct StageCost {
  const char* stage;
  double seconds_per_work;
  double seconds;  // fixed
};
// Tile sets: per atom of the copies the packers place (proteins and solubles). A patch's lipids cost
// next to nothing: a set of POPC with four spikes takes 0.03 CPU s for 10^6 lipid atoms.
constexpr StageCost kTileSets{"tile sets", 2.2e-6, 0.05};
// Shells: per membrane copy checked on the surface (clashes found atom by atom in chunks: 9-20 us measured).
constexpr StageCost kShells{"shells", 1.4e-5, 0.1};
constexpr StageCost kCoreGrids{"core grids", 3e-7, 0.05};     // per soluble copy in a boundary box
constexpr StageCost kPackage{"package content", 2.5e-8, 0.05};  // per atom of the copies in the sets (and writing)
// per node of the medium's exclusion fields (one a compartment, grid::ExclusionFieldRequest's
// budget): blood's two fields of ~10^6 nodes took 36-40 CPU s, an RBC microvesicle's one 9.8 s.
constexpr StageCost kMedium{"medium", 1.3e-5, 0.1};
// Of a patch's lipids, the share kept once the clashes of an equilibrated patch are resolved
// (clearance 0.6: the bundled scenes keep 72-78 %).
constexpr double kPatchLipidsKept = 0.75;
// Along a UV seam of a large membrane, the width (Å) over which copies are checked one by one.
constexpr double kSeamBand = 230.0;
// A membrane checked everywhere (tiles packed rigid) keeps each lipid put aside as alternates
// (tiles::kAlternatesPerLaidLipid); each is placed and its place looked up, and those standing where
// their lipid was dropped are tested: about 0.3 of a checked copy's work (a 0.13 µm² remeshed cube
// of 4·10⁵ lipids: shells 4.2 -> 12.7 CPU s, peak 178 -> 312 MB).
constexpr double kAlternateWork = 0.3;
constexpr double kBaseBytes = 45e6;  // the baker with its molecules read (knot_tube's "molecules" stage: 43 MB)
constexpr double kCompressionBytes = 64e6;  // zstd at its high levels, while the package is written
constexpr double kBytesPerTileAtom = 4.0;
constexpr double kBytesPerTriangle = 800.0;
// The copy as placed (96 bytes), its grid cell and its clash list, per copy the estimate counts
// (measured: the bundled RBC ~100, knot_tube ~120, an RBC surface of 0.55 µm² checked whole ~200, where
// the estimate counts 25 % fewer copies than are checked).
constexpr double kBytesPerCheckedCopy = 120.0;
constexpr double kBytesPerCoreBox = 2.0;
constexpr double kBytesPerInstance = 256.0;
// Of a stage's work, the share that runs on the worker threads.
constexpr double kParallelShare = 0.8;

double mean_atoms(const BakedLipidPatch& patch, const std::vector<BakedMolecule>& library) {
  double atoms = 0.0;
  for (const std::uint32_t m : patch.molecules) atoms += static_cast<double>(library[m].atoms.size());
  return patch.molecules.empty() ? 0.0 : atoms / static_cast<double>(patch.molecules.size());
}

// A membrane's lipids per Å² of surface (both leaflets), the atoms of one, and per species the
// share of the lipids.
struct MembraneLipids {
  double per_a2 = 0.0;
  double atoms = 0.0;
  std::vector<std::pair<std::string, double>> share;
};

MembraneLipids membrane_lipids(const scene::MembraneDescription& m, const std::optional<BakedLipidPatch>& patch,
                               const std::vector<BakedMolecule>& library) {
  MembraneLipids l;
  if (patch && patch->period_x > 0.0 && patch->period_y > 0.0) {
    l.per_a2 = static_cast<double>(patch->molecules.size()) / (patch->period_x * patch->period_y);
    l.atoms = mean_atoms(*patch, library);
    double mixed = 0.0;
    for (std::size_t k = 0; k < patch->mix.size(); ++k) {
      const double share = 0.5 * (patch->mix[k].outer + patch->mix[k].inner);
      l.share.emplace_back(m.lipid_mix[k].name, share);
      mixed += share;
    }
    if (m.lipid_patch->kinds.empty()) {
      l.share.insert(l.share.begin(), {m.lipid_patch->name, std::max(0.0, 1.0 - mixed)});
    } else {  // a patch of several kinds: each kind's share of the patch's own lipids
      const auto [outer, inner] = patch_leaflet_counts(*patch, library);
      const double all = static_cast<double>(patch->molecules.size());
      for (const scene::LeafletCounts* leaflet : {&outer, &inner})
        for (const auto& [kind, n] : *leaflet) named_entry(l.share, kind) += static_cast<double>(n) / all;
    }
  } else if (m.lipids) {
    l.per_a2 = 2.0 / m.lipids->area_per_lipid;
    l.atoms = static_cast<double>(library[m.lipids->molecule.index].atoms.size());
    l.share.emplace_back(m.lipids->molecule.name, 1.0);
  }
  return l;
}

std::string count_text(double n) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", n);
  return text;
}

std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, bytes >= 1e9 ? "%.2f GB" : "%.0f MB", bytes >= 1e9 ? bytes / 1e9 : bytes / 1e6);
  return text;
}

// The atoms of the copies in every tile and cube set: all of them (what the sets hold), and those the
// packers place one by one (proteins and solubles; a patch's lipids are laid as the patch has them).
struct SetAtoms {
  double all = 0.0, packed = 0.0;
};

// The work of the stages after the meshes, each in its own measure.
struct StageWork {
  SetAtoms tile_atoms;
  double checked_copies = 0.0, core_box_copies = 0.0, core_boxes = 0.0, triangles = 0.0;
  double medium_nodes = 0.0;  // of the exclusion fields (none without a medium)
};

struct EstimateInputs {
  const scene::SceneDescription& scene;
  const std::vector<BakedMolecule>& library;
  const std::vector<std::optional<BakedLipidPatch>>& patches;
  std::vector<MembraneLipids> lipids;  // per membrane
  std::vector<bool> sets_cached;       // per membrane, then per soluble (empty: none)

  bool set_cached(std::size_t k) const { return k < sets_cached.size() && sets_cached[k]; }
};

SetAtoms tile_set_atoms(const EstimateInputs& in) {
  const scene::SceneDescription& scene = in.scene;
  SetAtoms atoms;
  for (std::size_t i = 0; i < scene.membranes.size(); ++i) {
    const scene::MembraneDescription& m = scene.membranes[i];
    const double area = m.tiles * m.tile_size * m.tile_size;
    double protein_atoms_per_a2 = 0.0;
    for (const scene::MembraneProtein& p : m.proteins)
      protein_atoms_per_a2 += scene::copies_per_a2(m, p.abundance) * static_cast<double>(in.library[p.molecule.index].atoms.size());
    if (!in.set_cached(i)) atoms.packed += area * protein_atoms_per_a2;
    atoms.all += area * (protein_atoms_per_a2 + in.lipids[i].per_a2 * in.lipids[i].atoms);
  }
  for (std::size_t i = 0; i < scene.solubles.size(); ++i)
    for (const scene::SolubleMolecule& molecule : scene.solubles[i].molecules) {
      const scene::SolubleDescription& s = scene.solubles[i];
      const double n = s.cubes * std::pow(s.cube_size, 3) * scene::copies_per_a3(molecule.abundance) *
                       static_cast<double>(in.library[molecule.molecule.index].atoms.size());
      if (!in.set_cached(scene.membranes.size() + i)) atoms.packed += n;
      atoms.all += n;
    }
  return atoms;
}

// Adds the membrane's copies to `out`; returns how many of them the shells check.
double estimate_membrane(const EstimateInputs& in, std::size_t membrane, const EstimatedMesh& mesh, CompartmentEstimate& out) {
  const scene::MembraneDescription& m = in.scene.membranes[membrane];
  const MembraneLipids& l = in.lipids[membrane];
  const scene::CompartmentMeasure& measure = mesh.measure;
  double copies = 0.0;
  for (const scene::MembraneProtein& p : m.proteins) {
    double n = scene::copies_per_a2(m, p.abundance) * measure.area;
    if (p.per_compartment) n = std::min(n, static_cast<double>(*p.per_compartment));
    named_entry(out.copies, p.molecule.name) += n;
    copies += n;
  }
  const double lipid_copies = kPatchLipidsKept * l.per_a2 * measure.area;
  for (const auto& [name, share] : l.share) named_entry(out.copies, name) += share * lipid_copies;
  if (mesh.shells_cached) return 0.0;
  // The shells check the copies the triangles own before any is dropped: every place of the patch.
  const double owned = copies + l.per_a2 * measure.area;
  // The checked triangles (all of a membrane checked everywhere) and a band along the seams elsewhere.
  const double checked = owned * mesh.checked_share;
  if (mesh.checked_share >= 1.0) return checked + kAlternateWork * tiles::kAlternatesPerLaidLipid * l.per_a2 * measure.area;
  return checked + std::min(owned - checked, mesh.seam_length * kSeamBand * owned / measure.area);
}

// Adds the core grid's copies to `out` and its boxes to `work`; the solubles start `inset` inside the mesh.
void estimate_core(const EstimateInputs& in, std::size_t soluble, const scene::CompartmentMeasure& measure, double inset,
                   CompartmentEstimate& out, StageWork& work) {
  const scene::SolubleDescription& s = in.scene.solubles[soluble];
  const double cube = std::pow(s.cube_size, 3);
  const double boundary = measure.area / (s.cube_size * s.cube_size);
  work.core_boxes += std::max(0.0, measure.volume) / cube;
  for (const scene::SolubleMolecule& molecule : s.molecules) {
    const double reach = inset + s.clearance + in.library[molecule.molecule.index].properties.bounding_radius;
    const double volume = std::max(0.0, measure.volume - measure.area * reach);
    named_entry(out.copies, molecule.molecule.name) += scene::copies_per_a3(molecule.abundance) * volume;
    work.core_box_copies += boundary * scene::copies_per_a3(molecule.abundance) * cube;
  }
}

CompartmentEstimate estimate_compartment(const EstimateInputs& in, const scene::CompartmentDescription& description,
                                         const EstimatedMesh& mesh, StageWork& work) {
  const scene::CompartmentMeasure& measure = mesh.measure;
  CompartmentEstimate out;
  out.name = description.name;
  out.area_um2 = measure.area / kA2PerUm2;
  out.volume_um3 = std::max(0.0, measure.volume) / kA3PerUm3;
  work.triangles += static_cast<double>(measure.triangles);
  double inset = 0.0;  // how far inside the mesh the core grid's solubles start
  if (description.membrane) {
    work.checked_copies += estimate_membrane(in, description.membrane->index, mesh, out);
    inset = 0.5 * measure.bilayer_thickness;
  }
  if (description.soluble) estimate_core(in, description.soluble->index, measure, inset, out, work);
  return out;
}

double represented_atoms(const scene::SceneDescription& scene, const std::vector<CompartmentEstimate>& compartments,
                         const std::vector<BakedMolecule>& library) {
  double atoms = 0.0;
  for (const scene::InstanceEntry& entry : scene.instances) {
    const std::size_t c = std::holds_alternative<scene::ExplicitInstance>(entry)
                              ? std::get<scene::ExplicitInstance>(entry).compartment.index
                              : std::get<scene::RandomPlacement>(entry).compartment.index;
    const double n = std::holds_alternative<scene::ExplicitInstance>(entry) ? 1.0 : std::get<scene::RandomPlacement>(entry).count;
    double atoms_in_one = 0.0;
    for (const auto& [name, copies] : compartments[c].copies) {
      auto it = std::find_if(library.begin(), library.end(), [&](const BakedMolecule& b) { return b.name == name; });
      if (it != library.end()) atoms_in_one += copies * static_cast<double>(it->atoms.size());
    }
    atoms += n * atoms_in_one;
  }
  return atoms;
}

void add_stage_costs(const StageWork& work, BakeEstimate& e) {
  const auto stage = [&](const StageCost& cost, double amount) {
    e.stages.push_back({cost.stage, amount, cost.seconds + cost.seconds_per_work * amount});
  };
  stage(kTileSets, work.tile_atoms.packed);
  stage(kShells, work.checked_copies);
  stage(kCoreGrids, work.core_box_copies);
  stage(kPackage, work.tile_atoms.all);
  if (work.medium_nodes > 0) stage(kMedium, work.medium_nodes);
  const double threads = e.jobs;
  for (const StageEstimate& s : e.stages) {
    e.cpu_seconds += s.cpu_seconds;
    e.wall_seconds += s.cpu_seconds * ((1.0 - kParallelShare) + kParallelShare / threads);
  }
}

std::vector<MemoryTerm> memory_terms(const StageWork& w, std::uint64_t instances) {
  return {
      {"the baker itself", kBaseBytes, ""},
      {"compressing the package", kCompressionBytes, ""},
      {"tile and cube sets (" + count_text(w.tile_atoms.all) + " atoms of copies)", kBytesPerTileAtom * w.tile_atoms.all,
       "lower densities or concentrations, a smaller tile_size or cube_size, or fewer tiles or cubes"},
      {"meshes (" + count_text(w.triangles) + " triangles)", kBytesPerTriangle * w.triangles,
       "fewer triangles (\"triangles\", or \"remesh\": {\"edge\": ...} with a longer edge)"},
      {"membrane copies checked on the surface (" + count_text(w.checked_copies) + ")", kBytesPerCheckedCopy * w.checked_copies,
       "a smaller membrane or fewer copies on it"},
      {"core grids (" + count_text(w.core_boxes) + " boxes)", kBytesPerCoreBox * w.core_boxes, "a larger cube_size"},
      {"instances (" + count_text(static_cast<double>(instances)) + ")", kBytesPerInstance * static_cast<double>(instances),
       "fewer instances (\"count\")"},
  };
}

}  // namespace

double membrane_copies_for_pruning(double area, const scene::MembraneDescription& membrane,
                                   const std::optional<BakedLipidPatch>& patch) {
  double per_a2 = 0.0;
  if (patch && patch->period_x > 0 && patch->period_y > 0) per_a2 += patch->molecules.size() / (patch->period_x * patch->period_y);
  if (membrane.lipids && membrane.lipids->area_per_lipid > 0) per_a2 += 2.0 / membrane.lipids->area_per_lipid;
  for (const scene::MembraneProtein& p : membrane.proteins) per_a2 += scene::copies_per_a2(membrane, p.abundance);
  return area * per_a2;
}

BakeEstimate estimate_bake(const scene::SceneDescription& scene, const std::vector<BakedMolecule>& library,
                           const std::vector<std::optional<BakedLipidPatch>>& patches,
                           const std::vector<EstimatedMesh>& meshes, int jobs, const std::vector<bool>& sets_cached) {
  EstimateInputs in{scene, library, patches, {}, sets_cached};
  for (std::size_t i = 0; i < scene.membranes.size(); ++i)
    in.lipids.push_back(membrane_lipids(scene.membranes[i], patches[i], library));
  BakeEstimate e;
  StageWork work;
  work.tile_atoms = tile_set_atoms(in);
  for (std::size_t c = 0; c < scene.compartments.size(); ++c)
    e.compartments.push_back(estimate_compartment(in, scene.compartments[c], meshes[c], work));
  if (scene.medium) work.medium_nodes = double(scene.compartments.size()) * double(grid::ExclusionFieldRequest{}.max_nodes);
  e.instances = scene::expanded_instance_count(scene);
  e.represented_atoms = represented_atoms(scene, e.compartments, library);
  e.jobs = std::max(1, jobs);
  add_stage_costs(work, e);
  e.memory = memory_terms(work, e.instances);
  for (const MemoryTerm& t : e.memory) e.peak_bytes += t.bytes;
  return e;
}

std::string describe(const BakeEstimate& e) {
  std::ostringstream out;
  char line[512];
  std::snprintf(line, sizeof line,
                "estimate: about %.2g s with %d job(s) (%.0f CPU s) and %s of memory at the peak; %llu instance(s), %.3g "
                "represented atoms\n",
                e.wall_seconds, e.jobs, e.cpu_seconds, gigabytes(e.peak_bytes).c_str(),
                static_cast<unsigned long long>(e.instances), e.represented_atoms);
  out << line;
  for (const StageEstimate& s : e.stages) {
    std::snprintf(line, sizeof line, "  %s: %.3g CPU s (work %.3g)\n", s.stage.c_str(), s.cpu_seconds, s.work);
    out << line;
  }
  for (const CompartmentEstimate& c : e.compartments) {
    std::snprintf(line, sizeof line, "  %s: %.4g µm², %.4g µm³", c.name.c_str(), c.area_um2, c.volume_um3);
    out << line;
    for (const auto& [name, n] : c.copies) {
      std::snprintf(line, sizeof line, ", %s %.3g", name.c_str(), n);
      out << line;
    }
    out << "\n";
  }
  return out.str();
}

std::string over_memory_budget(const BakeEstimate& e, double max_bytes) {
  std::vector<MemoryTerm> terms = e.memory;
  std::sort(terms.begin(), terms.end(), [](const MemoryTerm& a, const MemoryTerm& b) { return a.bytes > b.bytes; });
  std::string rule = "the bake would take about " + gigabytes(e.peak_bytes) + " of memory at its peak, more than the " +
                     gigabytes(max_bytes) + " allowed (--max-memory; default: what the machine has available). Most of it:";
  for (const MemoryTerm& t : terms) {
    if (t.advice.empty() || t.bytes < 0.1 * e.peak_bytes) continue;
    rule += "\n  " + t.what + ": " + gigabytes(t.bytes) + "; to shrink it: " + t.advice;
  }
  return rule;
}

std::optional<double> parse_byte_size(const std::string& text) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  std::string unit = text.substr(used);
  for (char& ch : unit) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  if (!unit.empty() && unit.back() == 'B') unit.pop_back();
  if (!unit.empty() && unit.back() == 'I') unit.pop_back();  // "GiB"
  double factor = 1.0;
  if (unit == "K") factor = 1024.0;
  else if (unit == "M") factor = 1024.0 * 1024.0;
  else if (unit == "G") factor = 1024.0 * 1024.0 * 1024.0;
  else if (unit == "T") factor = 1024.0 * 1024.0 * 1024.0 * 1024.0;
  else if (!unit.empty()) return std::nullopt;
  if (!(value > 0.0) || !std::isfinite(value)) return std::nullopt;
  return value * factor;
}

double available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kb = 0.0;
  std::string unit;
  while (meminfo >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024.0;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

double process_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

double peak_resident_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return 1024.0 * static_cast<double>(usage.ru_maxrss);  // Linux: KiB
}

}  // namespace nano::scene_bake
