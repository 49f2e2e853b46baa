#include "bake/scene_bake/scene_baker.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "bake/mesh/uv_distortion.hpp"
#include "bake/mesh/vertex_normals.hpp"
#include "bake/scene/medium_region.hpp"
#include "bake/scene/random_placement.hpp"
#include "bake/scene_bake/bake_invariants.hpp"
#include "bake/scene_bake/compartment_mesh.hpp"
#include "bake/scene_bake/core_bake.hpp"
#include "bake/scene_bake/membrane_bake.hpp"
#include "bake/scene_bake/membrane_surface.hpp"
#include "bake/scene_bake/molecule_measures.hpp"
#include "bake/scene_bake/named_totals.hpp"
#include "bake/scene_bake/provenance.hpp"
#include "bake/tiles/bilayer_footprint.hpp"
#include "bake/tiles/tile_random.hpp"
#include "common/error.hpp"
#include "common/parallel_for.hpp"
#include "common/progress.hpp"

namespace nano::scene_bake {
namespace {

// Every random choice of the bake derives from the scene seed and a tag naming what it seeds.
enum class SeedTag : std::uint64_t { membrane_tiles = 1, soluble_cubes, membrane_recipe, soluble_recipe, medium_recipe };

std::uint64_t derive_seed(std::uint64_t seed, SeedTag tag, std::size_t index) {
  return tiles::mix64(seed ^ tiles::mix64(static_cast<std::uint64_t>(tag) * 0x100000001B3ull + index));
}

class StageClock {
public:
  StageClock(BakedScene& scene, const BakeOptions& options) : scene_(scene), options_(options) {}

  template <class F>
  auto run(const std::string& stage, F&& work) {
    progress::reset();
    if (options_.on_stage_begin) options_.on_stage_begin(stage);
    const auto start = std::chrono::steady_clock::now();
    struct Record {
      StageClock& clock;
      const std::string& stage;
      std::chrono::steady_clock::time_point start;
      double cpu_start;
      ~Record() {
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        named_entry(clock.scene_.stage_seconds, stage) += seconds;
        named_entry(clock.scene_.stage_cpu_seconds, stage) += process_cpu_seconds() - cpu_start;
        named_entry(clock.scene_.stage_peak_bytes, stage) = peak_resident_bytes();  // the process's peak so far
        if (clock.options_.on_stage_end) clock.options_.on_stage_end(stage, seconds);
      }
    } record{*this, stage, start, process_cpu_seconds()};
    return work();
  }

private:
  BakedScene& scene_;
  const BakeOptions& options_;
};

struct CompartmentBake {
  CompartmentMesh mesh;
  MeshSurfacePlan surface;  // how its membrane's tiles meet it (membrane_surface.hpp)
  bool surface_whole = true;  // its membrane is checked copy by copy everywhere
  std::optional<BakedMembrane> membrane;
  std::optional<BakedCore> core;
  double shell_margin = 0.0;  // how far copies reach outside the mesh (Å)
};

// How far the patch's lipid centres stand from its mid-plane, on average, in each leaflet (Å).
struct LeafletDepths {
  double outer = 0.0, inner = 0.0;
};
LeafletDepths lipid_centre_depths(const BakedLipidPatch& patch) {
  double sum[2] = {0.0, 0.0};
  std::size_t count[2] = {0, 0};
  for (const glm::dvec3& p : patch.positions) {
    const int side = p.z >= 0.0 ? 0 : 1;
    sum[side] += std::abs(p.z);
    ++count[side];
  }
  return {count[0] ? sum[0] / static_cast<double>(count[0]) : 0.0, count[1] ? sum[1] / static_cast<double>(count[1]) : 0.0};
}

MembraneSummary membrane_summary(const mesh::ProxyMesh& mesh, const BakedMembrane& m, const BakedWangSet& tiles,
                                 const std::vector<BakedMolecule>& library, const std::optional<BakedLipidPatch>& patch,
                                 const scene::MembraneDescription& membrane) {
  MembraneSummary s;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) s.area_um2 += mesh::world_area(mesh, t) * 1e-8;
  // Per library molecule: 0 not a lipid, +1 an outer-leaflet lipid, -1 an inner one (a patch
  // conformer's leaflet is the side of the mid-plane its centroid stands on).
  std::vector<int> lipid(library.size(), 0);
  const auto mark = [&](const BakedLipidPatch& p) {
    for (std::size_t i = 0; i < p.molecules.size(); ++i) lipid[p.molecules[i]] = p.positions[i].z >= 0.0 ? 1 : -1;
  };
  if (patch) {
    mark(*patch);
    for (const BakedLipidPatch& species : patch->mix) mark(species);
    const LeafletDepths depths = lipid_centre_depths(*patch);
    s.outer_area_um2 = mesh::offset_surface_area(mesh, depths.outer) * 1e-8;
    s.inner_area_um2 = mesh::offset_surface_area(mesh, -depths.inner) * 1e-8;
  }
  if (membrane.lipids) lipid[membrane.lipids->molecule.index] = 1;  // both leaflets: counted as outer
  for (std::size_t i = 0; i < library.size(); ++i) {
    if (lipid[i] != 0 && m.copies_by_molecule[i] > 0) {
      named_entry(s.lipids, library[i].name) += m.copies_by_molecule[i];
      (lipid[i] > 0 ? s.outer_lipids : s.inner_lipids) += m.copies_by_molecule[i];
      named_entry(lipid[i] > 0 ? s.outer_kinds : s.inner_kinds, library[i].name) += m.copies_by_molecule[i];
    }
    if (m.dropped_by_molecule[i] > 0) named_entry(s.dropped, library[i].name) += m.dropped_by_molecule[i];
    if (m.alternates_by_molecule[i] > 0) named_entry(s.alternates, library[i].name) += m.alternates_by_molecule[i];
    if (m.unfit_by_molecule[i] > 0) named_entry(s.unfit, library[i].name) += m.unfit_by_molecule[i];
  }
  s.real_outer_per_um2 = s.real_inner_per_um2 = 0.5 * kRealBilayerLipidsPerUm2;
  if (membrane.lipid_patch && membrane.lipid_patch->outer_leaflet && membrane.lipid_patch->inner_leaflet) {
    s.real_outer_per_um2 = 1e8 / membrane.lipid_patch->outer_leaflet->area_per_lipid;  // Å² -> µm²
    s.real_inner_per_um2 = 1e8 / membrane.lipid_patch->inner_leaflet->area_per_lipid;
  }
  if (membrane.lipids) {  // one pose in both leaflets: split evenly
    s.inner_lipids += s.outer_lipids / 2;
    s.outer_lipids -= s.outer_lipids / 2;
  }
  // Each protein stands at its depth, turned only about the normal: one tile copy gives its footprint.
  std::vector<tiles::MoleculeType> types;
  for (const std::uint32_t lib : tiles.molecule_of_type) types.push_back(to_tile_molecule(library[lib]));
  std::vector<char> measured(types.size(), 0);
  for (const tiles::WangTile& tile : tiles.set.tiles)
    for (const tiles::Instance& in : tile.instances) {
      const std::uint32_t lib = tiles.molecule_of_type[in.type];
      if (measured[in.type] || lipid[lib] != 0) continue;
      measured[in.type] = 1;
      const double copies = static_cast<double>(m.copies_by_molecule[lib]) * 1e-8;  // Å² -> µm²
      s.outer_protein_um2 += copies * tiles::leaflet_footprint(types[in.type], in, tiles::outer_leaflet(kLeafletHalfThickness));
      s.inner_protein_um2 += copies * tiles::leaflet_footprint(types[in.type], in, tiles::inner_leaflet(kLeafletHalfThickness));
    }
  s.pruned_everywhere = m.pruning.whole_surface;
  s.checked_triangles = m.pruning.checked_triangles;
  s.triangles = mesh.triangles.size();
  s.checked_copies = m.pruning.checked_copies;
  s.atom_pairs = m.pruning.atom_pairs;
  s.copy_pairs_tested = m.pruning.copy_pairs_tested;
  return s;
}

std::uint32_t largest_tile(const BakedWangSet& set) {
  std::size_t largest = 0;
  for (const tiles::WangTile& t : set.set.tiles) largest = std::max(largest, t.instances.size());
  return static_cast<std::uint32_t>(largest);
}

void world_aabb(const scene::Matrix3x4& m, const glm::dvec3& lo, const glm::dvec3& hi, InstanceSummary& out) {
  out.aabb_min = glm::dvec3(std::numeric_limits<double>::max());
  out.aabb_max = glm::dvec3(-std::numeric_limits<double>::max());
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z};
    const glm::dvec3 w = scene::transform_point(m, p);
    out.aabb_min = glm::min(out.aabb_min, w);
    out.aabb_max = glm::max(out.aabb_max, w);
  }
}

std::uint32_t effect_flags(const scene::Effects& effects) {
  std::uint32_t flags = 0;
  if (effects.clipping) flags |= effect_declaration(EffectId::clipping).package_flag;
  if (effects.animation && effects.animation->moves()) flags |= effect_declaration(EffectId::animation).package_flag;
  for (const EffectDeclaration& effect : effect_table())
    if (effects.sets(effect.id)) flags |= effect.package_flag;
  return flags;
}

// The parameters of the effects the flags turn on (format section "effects"); none when all are off.
std::vector<gpu::SceneEffects> scene_effects(const scene::Effects& effects) {
  if (effect_flags(effects) == 0) return {};
  gpu::SceneEffects e{};
  if (const auto& clip = effects.clipping) {
    // Invariant, not input: the scene parser refuses more planes, naming the key.
    if (clip->planes.size() > gpu::NANO_MAX_CLIP_PLANES)
      throw std::invalid_argument("scene_effects: more clip planes than the parser lets through (at most 8)");
    for (std::size_t k = 0; k < clip->planes.size(); ++k) e.clip_planes[k] = glm::vec4(clip->planes[k]);
    e.clip_plane_count = static_cast<std::uint32_t>(clip->planes.size());
    if (clip->box) {
      e.clip_box_min = glm::vec4(glm::vec3(clip->box->min), 1.f);
      e.clip_box_max = glm::vec4(glm::vec3(clip->box->max), 0.f);
    }
  }
  if (const auto& a = effects.animation) {
    if (a->steady && a->keyframes.empty()) {
      e.spin = glm::vec4(glm::vec3(a->steady->spin_axis), static_cast<float>(a->steady->spin_degrees_per_second));
      if (e.spin.w == 0.f) e.spin = glm::vec4(0.f);
      e.velocity = glm::vec4(glm::vec3(a->steady->velocity), 0.f);
    }
  }
  for (const EffectDeclaration& effect : effect_table())
    if (effects.sets(effect.id)) copy_parameters(e, effects.parameters, effect.id);
  return {e};
}

// Keyframed proxy motion, ascending by (instance, time) as the format asks.
std::vector<gpu::InstanceKeyframe> scene_keyframes(const scene::Effects& effects) {
  std::vector<gpu::InstanceKeyframe> keys;
  if (!effects.animation) return keys;
  for (const scene::InstanceKeyframes& track : effects.animation->keyframes)
    for (const scene::Keyframe& k : track.keys) {
      gpu::InstanceKeyframe record{};
      for (int row = 0; row < 3; ++row) record.transform[row] = glm::vec4(k.transform[row]);
      record.time = static_cast<float>(k.time);
      record.instance = static_cast<std::uint32_t>(track.instance);
      keys.push_back(record);
    }
  std::stable_sort(keys.begin(), keys.end(), [](const auto& a, const auto& b) { return a.instance < b.instance; });
  return keys;
}

gpu::SceneSettings scene_settings(const scene::SceneDescription& scene, const std::vector<InstanceSummary>& instances) {
  gpu::SceneSettings settings{};
  settings.effect_flags = effect_flags(scene.effects);
  Camera camera;
  if (scene.camera) {
    camera = *scene.camera;
  } else {
    // Frame every instance from +z with a little margin.
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const InstanceSummary& i : instances) {
      lo = glm::min(lo, i.aabb_min);
      hi = glm::max(hi, i.aabb_max);
    }
    if (instances.empty()) lo = hi = glm::dvec3(0.0);
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const double radius = std::max(0.5 * glm::length(hi - lo), 1.0);
    camera.fov_degrees = kDefaultFovDegrees;
    camera.look_at = centre;
    camera.position = centre + glm::dvec3(0.0, 0.0, 1.1 * radius / std::tan(glm::radians(camera.fov_degrees) / 2));
    camera.up = {0.0, 1.0, 0.0};
  }
  store_camera(settings, camera);
  return settings;
}

BakedScene bake_described_scene(const scene::SceneDescription& scene, const BakeOptions& options);

}  // namespace

BakedScene bake_scene(const scene::SceneDescription& scene, const BakeOptions& options) {
  try {
    return bake_described_scene(scene, options);
  } catch (const InputError& e) {
    // A rule about a scene key (a Wang set's tiles, a core grid's cubes) is the scene file's.
    if (!e.file().empty() || scene.source.empty()) throw;
    throw InputError(scene.source.string(), e.where(), e.rule());
  }
}

namespace {

// What every stage reads: the scene, how to bake it, and the seed and jobs the options settle.
struct BakeInputs {
  const scene::SceneDescription& scene;
  const BakeOptions& options;
  std::uint64_t seed;
  int threads;
};

// The molecules stage: the library, each membrane's lipid patch (with its mix), and the sizes the
// feasibility checks weigh the meshes against.
struct Molecules {
  std::vector<BakedMolecule> library;
  std::vector<std::optional<BakedLipidPatch>> patches;  // per membrane
  std::vector<scene::MoleculeMeasure> measures;
};

Molecules load_molecules(const scene::SceneDescription& scene) {
  Molecules m;
  m.patches.resize(scene.membranes.size());
  m.library = load_molecule_library(scene);
  for (std::size_t i = 0; i < scene.membranes.size(); ++i)
    if (const auto& patch = scene.membranes[i].lipid_patch) {
      m.patches[i] = load_lipid_patch(*patch, m.library.size(), m.library);
      for (const scene::LipidPatchDescription& species : scene.membranes[i].lipid_mix) {
        BakedLipidPatch mixed = load_lipid_patch(species, m.library.size(), m.library);
        mixed.outer = species.outer;
        mixed.inner = species.inner;
        m.patches[i]->mix.push_back(std::move(mixed));
      }
      const auto [outer, inner] = patch_leaflet_counts(*m.patches[i], m.library);
      scene::check_leaflet_shares(scene, i, outer, inner, "the patch file holds");
    }
  m.measures = measure_molecules(scene, m.library);
  scene::check_molecule_amounts(scene, m.measures);
  return m;
}

CompartmentMesh load_mesh(const BakeInputs& in, const Molecules& molecules, std::size_t c) {
  std::optional<double> thickness;
  if (const auto& membrane = in.scene.compartments[c].membrane)
    thickness = membrane_bilayer_thickness(in.scene.membranes[membrane->index], molecules.patches[membrane->index],
                                           molecules.library);
  CompartmentMesh loaded = load_compartment_mesh(in.scene.compartments[c], thickness, [&](const mesh::ProxyMesh& m) {
    scene::CompartmentMeasure measure = measure_compartment(m);
    measure.bilayer_thickness = thickness.value_or(0.0);
    scene::check_compartment_amounts(in.scene, c, measure, molecules.measures);
  });
  if (in.options.mesh_codec != MeshCodec::zstd) put_on_storage_grids(loaded);
  else loaded.storage = "exact as read (--mesh-codec zstd)";
  if (in.options.mesh_codec == MeshCodec::draco && !loaded.on_storage_grids)
    throw InputError(loaded.origin, "", "--mesh-codec draco: " + loaded.storage);
  return loaded;
}

// Each mesh is measured once, after the meshes stage: the estimate, the choice of where to prune and
// the placements all read these.
struct MeshMeasures {
  std::vector<scene::CompartmentMeasure> measures;
  std::vector<double> radii;  // each mesh's extent
};

MeshMeasures measure_meshes(const std::vector<CompartmentBake>& compartments) {
  MeshMeasures out;
  for (const CompartmentBake& c : compartments) {
    out.measures.push_back(measure_compartment(c.mesh.mesh));
    out.measures.back().bilayer_thickness = c.mesh.bilayer_thickness;
    out.radii.push_back(out.measures.back().extent);
  }
  return out;
}

void check_placements(const scene::SceneDescription& scene, const Molecules& molecules, const MeshMeasures& measured) {
  scene::check_placement_amounts(scene, measured.radii);
  // A trial of the random placements with the meshes' own radii (the real one, after the shells,
  // adds their margin): a box too crowded to fill, or a medium around nothing, is refused now, not
  // after the heavy stages.
  if (scene::expanded_instance_count(scene) == scene.instances.size() && !scene.medium) return;
  const std::vector<scene::PlacedInstance> trial = scene::expand_random_instances(scene, measured.radii);
  scene::check_medium_region(scene, molecules.measures, scene::instance_spheres(trial, measured.radii));
}

// Before the heavy stages; again after the shells when the bake cache served some shells or tile
// sets (their flags set: `sets_cached` per membrane, then per soluble).
BakeEstimate estimate(const BakeInputs& in, const Molecules& molecules, const std::vector<CompartmentBake>& compartments,
                      const MeshMeasures& measured, const std::vector<bool>& sets_cached = {}) {
  std::vector<EstimatedMesh> meshes;
  for (std::size_t c = 0; c < compartments.size(); ++c)
    meshes.push_back({measured.measures[c], compartments[c].mesh.report.seam_length,
                      compartments[c].surface.area > 0.0 ? compartments[c].surface.checked_area / compartments[c].surface.area : 1.0,
                      compartments[c].membrane && compartments[c].membrane->shells_from_cache});
  return estimate_bake(in.scene, molecules.library, molecules.patches, meshes, in.threads, sets_cached);
}

// Each membrane planned over the meshes that wear it (membrane_surface.hpp): small membranes (a
// virion's) are packed rigid, as dense as the patch, and checked copy by copy on their real surface
// everywhere; a large one (a cell's 10^8 lipids) is packed to survive what its charts do and checked
// along its seams and where its meshes distort more than tiles can be packed for. Each compartment
// keeps its mesh's part of the plan; the packing bounds are returned per membrane.
std::vector<tiles::SurfaceDistortion> plan_membranes(const BakeInputs& in, const Molecules& molecules,
                                                     std::vector<CompartmentBake>& compartments) {
  const scene::SceneDescription& scene = in.scene;
  std::vector<tiles::SurfaceDistortion> surfaces(scene.membranes.size());
  for (std::size_t m = 0; m < scene.membranes.size(); ++m) {
    std::vector<std::size_t> wearing;
    std::vector<const mesh::ProxyMesh*> meshes;
    for (std::size_t c = 0; c < scene.compartments.size(); ++c)
      if (const auto& membrane = scene.compartments[c].membrane; membrane && membrane->index == m) {
        wearing.push_back(c);
        meshes.push_back(&compartments[c].mesh.mesh);
      }
    if (wearing.empty()) continue;
    MembraneSurfacePlan plan =
        plan_membrane_surface(meshes, membrane_copies_for_pruning(1.0, scene.membranes[m], molecules.patches[m]),
                              kMembraneSurfaceSmoothness, double(shell::PruningSettings{}.whole_surface_budget), in.threads);
    surfaces[m] = plan.pack_for;
    for (std::size_t k = 0; k < wearing.size(); ++k) {
      compartments[wearing[k]].surface = std::move(plan.meshes[k]);
      compartments[wearing[k]].surface_whole = plan.whole_surface;
    }
  }
  return surfaces;
}

struct TileSets {
  std::vector<BakedWangSet> membrane, soluble;  // indexed like the scene's membranes and solubles
};

// Every Wang set is generated on its own (own seed, shared read-only inputs), so the sets run side by
// side on the jobs, and each spreads its own work over them too: a membrane's set is most of the stage.
TileSets bake_tile_sets(const BakeInputs& in, const Molecules& molecules,
                        const std::vector<tiles::SurfaceDistortion>& surfaces) {
  const scene::SceneDescription& scene = in.scene;
  const std::size_t membrane_count = scene.membranes.size();
  TileSets sets{std::vector<BakedWangSet>(membrane_count), std::vector<BakedWangSet>(scene.solubles.size())};
  parallel_for(membrane_count + scene.solubles.size(), in.threads, [&](std::size_t k) {
    if (k < membrane_count) {
      const auto& patch = molecules.patches[k];
      sets.membrane[k] = bake_membrane_tiles(scene.membranes[k], molecules.library, patch ? &*patch : nullptr,
                                             surfaces[k], derive_seed(in.seed, SeedTag::membrane_tiles, k), in.threads,
                                             in.options.cache_directory);
    } else {
      const std::size_t i = k - membrane_count;
      sets.soluble[i] = bake_soluble_cubes(scene.solubles[i], molecules.library, derive_seed(in.seed, SeedTag::soluble_cubes, i),
                                           in.threads, in.options.cache_directory);
    }
  });
  return sets;
}

void summarise_tile_sets(BakedScene& baked, const scene::SceneDescription& scene, const TileSets& sets,
                         const std::vector<tiles::SurfaceDistortion>& surfaces) {
  for (std::size_t i = 0; i < sets.membrane.size(); ++i)
    baked.wang_sets.push_back({scene.membranes[i].name, sets.membrane[i].set.densities, surfaces[i], sets.membrane[i].from_cache});
  for (std::size_t i = 0; i < sets.soluble.size(); ++i)
    baked.wang_sets.push_back({scene.solubles[i].name, sets.soluble[i].set.densities, std::nullopt, sets.soluble[i].from_cache});
}

BakedMembrane bake_shell(const BakeInputs& in, const Molecules& molecules, const TileSets& sets, std::size_t c,
                         CompartmentBake& bake) {
  const scene::CompartmentDescription& description = in.scene.compartments[c];
  const std::size_t membrane = description.membrane->index;
  PerCompartment per_compartment;
  for (const scene::MembraneProtein& p : in.scene.membranes[membrane].proteins)
    if (p.per_compartment) per_compartment.emplace_back(static_cast<std::uint32_t>(p.molecule.index), *p.per_compartment);
  try {
    return bake_membrane(bake.mesh.mesh, sets.membrane[membrane], {bake.surface, bake.surface_whole}, molecules.library,
                         derive_seed(in.seed, SeedTag::membrane_recipe, c), in.threads, per_compartment,
                         in.options.cache_directory);
  } catch (const InputError& e) {
    // What the membrane cannot do on this mesh is the mesh's file's business, not an anonymous input's.
    if (!e.file().empty()) throw;
    throw InputError(bake.mesh.origin, "compartment '" + description.name + "' " + e.where(), e.rule());
  }
}

// How far the membrane's copies reach outside the mesh (Å).
double shell_margin(const BakedMembrane& membrane) {
  double margin = 0.0;
  for (const gpu::TriangleShell& s : membrane.shells) margin = std::max({margin, double(s.h_plus), double(s.side_offset)});
  return margin;
}

BakedCore bake_core_grid(const BakeInputs& in, const Molecules& molecules, const TileSets& sets, std::size_t c,
                         const CompartmentBake& bake) {
  const std::size_t soluble = in.scene.compartments[c].soluble->index;
  const double inner = bake.membrane ? bake.membrane->inner_height : 0.0;
  return bake_core(bake.mesh.mesh, sets.soluble[soluble], in.scene.solubles[soluble], molecules.library, inner,
                   derive_seed(in.seed, SeedTag::soluble_recipe, c), in.threads);
}

std::vector<scene::PlacedInstance> place_instances(const scene::SceneDescription& scene,
                                                   const std::vector<CompartmentBake>& compartments,
                                                   const MeshMeasures& measured) {
  std::vector<double> radii;
  for (std::size_t c = 0; c < compartments.size(); ++c) radii.push_back(measured.radii[c] + compartments[c].shell_margin);
  return scene::expand_random_instances(scene, radii);
}

// The medium around the placed instances: its region from their spheres (meshes and shells), one
// exclusion field per compartment.
BakedMedium bake_scene_medium(const BakeInputs& in, const Molecules& molecules, const TileSets& sets,
                              const std::vector<CompartmentBake>& compartments, const MeshMeasures& measured,
                              const std::vector<scene::PlacedInstance>& placed) {
  const scene::SceneDescription& scene = in.scene;
  std::vector<double> radii;
  std::vector<MediumCompartment> walls;
  for (std::size_t c = 0; c < compartments.size(); ++c) {
    radii.push_back(measured.radii[c] + compartments[c].shell_margin);
    walls.push_back({&compartments[c].mesh.mesh, compartments[c].membrane ? compartments[c].membrane->reach : std::vector<float>{}});
  }
  const scene::Box region = scene::medium_region(scene, scene::instance_spheres(placed, radii));
  return bake_medium(scene, region, sets.soluble[scene.medium->soluble.index], molecules.library, walls, placed,
                     derive_seed(in.seed, SeedTag::medium_recipe, 0), in.threads);
}

MediumSummary medium_summary(const scene::SceneDescription& scene, const BakedMedium& m) {
  MediumSummary s;
  s.soluble = scene.solubles[scene.medium->soluble.index].name;
  s.region_min = m.region.min;
  s.region_max = m.region.max;
  s.boxes = m.boxes;
  s.copies_in_region = m.copies_in_region;
  for (const MediumMoleculeCount& n : m.counts) s.counts.push_back(n);
  for (std::size_t c = 0; c < m.fields.size(); ++c)
    s.fields.push_back({scene.compartments[c].name, m.fields[c].spacing, m.fields[c].margin, m.fields[c].measured_excess,
                        m.fields[c].least_reach, m.fields[c].largest_reach, m.fields[c].values.size() * sizeof(float) + sizeof(gpu::ExclusionField)});
  return s;
}

// What the package content stage writes from: every earlier stage's result.
struct PackageInputs {
  const BakeInputs& in;
  const Molecules& molecules;
  const TileSets& sets;
  const std::vector<CompartmentBake>& compartments;
  const std::optional<BakedMedium>& medium;
};

struct TileSetRanges {
  std::vector<TileRange> membrane, soluble;  // where each set's tiles lie in the package
};

// One compartment's record, what the bake report says of it, and its copies per library molecule.
struct CompartmentContent {
  gpu::Compartment record{};
  CompartmentSummary summary;
  std::vector<std::uint64_t> copies;
};

format::Compression mesh_compression(MeshCodec codec) {
  return codec == MeshCodec::zstd    ? format::Compression::zstd_if_smaller
         : codec == MeshCodec::draco ? format::Compression::draco
                                     : format::Compression::draco_if_smaller;
}

CompartmentSummary mesh_summary(const std::string& name, const CompartmentMesh& mesh) {
  CompartmentSummary summary;
  summary.name = name;
  summary.mesh_origin = mesh.origin;
  summary.mesh_scale = mesh.scale;
  summary.uv_origin = mesh.uv_origin;
  summary.mesh_storage = mesh.storage;
  summary.bilayer_thickness = mesh.bilayer_thickness;
  summary.thinnest_wall = mesh.thinnest_wall;
  summary.charts = mesh.charts;
  summary.repair = mesh.repair;
  summary.remesh = mesh.remesh;
  summary.triangles = static_cast<std::uint32_t>(mesh.mesh.triangles.size());
  return summary;
}

void add_membrane(PackageContent& content, const BakedMembrane& m, TileRange range, CompartmentContent& out) {
  gpu::Compartment& record = out.record;
  record.membrane_first_tile = range.first;
  record.membrane_tile_count = range.count;
  record.membrane_recipe = content.add_recipe(m.recipe, range);
  record.replication_width = m.replication_width;
  record.replication_height = m.replication_height;
  record.scales.x = static_cast<float>(m.uv_scale);
  record.scales.y = static_cast<float>(m.tile_size);
  record.scales.w = m.smooth;
  for (std::size_t i = 0; i < out.copies.size(); ++i) out.copies[i] += m.copies_by_molecule[i];
  out.summary.replication_width = m.replication_width;
  out.summary.replication_height = m.replication_height;
}

void add_core(PackageContent& content, const BakedCore& core, TileRange range, std::uint32_t largest_cube,
              CompartmentContent& out) {
  gpu::Compartment& record = out.record;
  const grid::CoreGrid& grid = core.occupancy.grid;
  record.soluble_first_tile = range.first;
  record.soluble_tile_count = range.count;
  record.soluble_recipe = content.add_recipe(core.recipe, range);
  record.scales.z = static_cast<float>(grid.box_size);
  record.grid_min = glm::vec4(glm::vec3(grid.min), static_cast<float>(grid.box_size));
  std::vector<std::uint8_t> classes(core.occupancy.classes.size());
  std::transform(core.occupancy.classes.begin(), core.occupancy.classes.end(), classes.begin(),
                 [](grid::BoxClass b) { return static_cast<std::uint8_t>(b); });
  record.grid_dims = glm::uvec4(glm::uvec3(grid.dims), content.add_occupancy(classes));
  const auto [first, count] = content.add_keep_masks(core.masks, largest_cube);
  record.core_masks = glm::uvec4(first, count, 0u, 0u);
  for (std::size_t i = 0; i < out.copies.size(); ++i) out.copies[i] += core.copies_by_molecule[i];
  out.summary.core_boxes_inside = core.occupancy.inside;
  out.summary.core_boxes_boundary = core.occupancy.boundary;
}

// By name: a lipid patch's conformers are one kind of molecule to a reader.
void count_copies(const std::vector<BakedMolecule>& library, CompartmentContent& out) {
  CompartmentSummary& summary = out.summary;
  for (std::size_t i = 0; i < library.size(); ++i) {
    if (out.copies[i] == 0) continue;
    auto named = std::find_if(summary.copies.begin(), summary.copies.end(),
                              [&](const auto& entry) { return entry.first == library[i].name; });
    if (named == summary.copies.end()) summary.copies.emplace_back(library[i].name, out.copies[i]);
    else named->second += out.copies[i];
    summary.represented_atoms += out.copies[i] * library[i].atoms.size();
  }
}

CompartmentContent compartment_content(PackageContent& content, const PackageInputs& p, const TileSetRanges& ranges,
                                       std::size_t c) {
  const scene::CompartmentDescription& description = p.in.scene.compartments[c];
  const CompartmentBake& bake = p.compartments[c];
  const std::vector<BakedMolecule>& library = p.molecules.library;
  CompartmentContent out;
  out.record.membrane_recipe = out.record.soluble_recipe = gpu::NANO_NO_INDEX;
  const PackedMesh packed = bake.mesh.on_storage_grids ? pack_mesh_canonical(bake.mesh.mesh) : pack_mesh(bake.mesh.mesh);
  out.record.mesh = bake.membrane ? content.add_mesh(packed, bake.membrane->shells, bake.membrane->dropped)
                                  : content.add_mesh(packed, empty_shells(bake.mesh.mesh));
  std::tie(out.record.name_offset, out.record.name_length) = content.add_string(description.name);
  out.copies.assign(library.size(), 0);
  out.summary = mesh_summary(description.name, bake.mesh);
  if (bake.membrane) {
    out.summary.shells_from_cache = bake.membrane->shells_from_cache;
    const std::size_t m = description.membrane->index;
    add_membrane(content, *bake.membrane, ranges.membrane[m], out);
    out.summary.membrane = membrane_summary(bake.mesh.mesh, *bake.membrane, p.sets.membrane[m], library,
                                            p.molecules.patches[m], p.in.scene.membranes[m]);
  }
  if (bake.core) {
    const std::size_t s = description.soluble->index;
    add_core(content, *bake.core, ranges.soluble[s], largest_tile(p.sets.soluble[s]), out);
  }
  count_copies(library, out);
  return out;
}

void add_instance(BakedScene& baked, const scene::PlacedInstance& p, const CompartmentBake& bake) {
  PackageContent& content = baked.content;
  gpu::CompartmentInstance record{};
  for (int row = 0; row < 3; ++row) record.transform[row] = glm::vec4(p.transform[row]);
  record.compartment = static_cast<std::uint32_t>(p.compartment.index);
  content.compartment_instances.push_back(record);
  const glm::dvec3 margin(bake.shell_margin);
  InstanceSummary summary;
  summary.compartment = p.compartment.name;
  const gpu::Mesh& mesh = content.meshes[content.compartments[p.compartment.index].mesh];
  const glm::vec3 lo = glm::vec3(mesh.aabb_min);
  const glm::vec3 hi = glm::vec3(mesh.aabb_max);
  world_aabb(p.transform, glm::dvec3(lo) - margin, glm::dvec3(hi) + margin, summary);
  baked.instances.push_back(summary);
  baked.represented_atoms += baked.compartments[p.compartment.index].represented_atoms;
}

void fill_package_content(BakedScene& baked, const PackageInputs& p, const std::vector<scene::PlacedInstance>& placed) {
  PackageContent& content = baked.content;
  const std::vector<BakedMolecule>& library = p.molecules.library;
  content.mesh_compression = mesh_compression(p.in.options.mesh_codec);
  for (const BakedMolecule& m : library) content.add_molecule(m);
  TileSetRanges ranges;
  for (const BakedWangSet& s : p.sets.membrane) ranges.membrane.push_back(content.add_wang_set(s, library));
  for (const BakedWangSet& s : p.sets.soluble) ranges.soluble.push_back(content.add_wang_set(s, library));
  for (std::size_t c = 0; c < p.compartments.size(); ++c) {
    CompartmentContent compartment = compartment_content(content, p, ranges, c);
    content.compartments.push_back(compartment.record);
    baked.compartments.push_back(std::move(compartment.summary));
  }
  content.add_core_skip();
  for (const scene::PlacedInstance& instance : placed) add_instance(baked, instance, p.compartments[instance.compartment.index]);
  if (p.medium) {
    const std::size_t s = p.in.scene.medium->soluble.index;
    content.add_medium(*p.medium, ranges.soluble[s], largest_tile(p.sets.soluble[s]));
    baked.medium = medium_summary(p.in.scene, *p.medium);
    for (const MediumMoleculeCount& n : p.medium->counts) baked.represented_atoms += static_cast<std::uint64_t>(n.atoms);
  }
  const scene::SceneDescription& scene = p.in.scene;
  content.scene = scene_settings(scene, baked.instances);
  content.effects = scene_effects(scene.effects);
  content.keyframes = scene_keyframes(scene.effects);
  content.provenance = provenance_json(scene, p.in.seed);
}

// The stages, in the order the bake report names them; the estimate (and --dry-run's stop) between
// the meshes and the heavy stages, once the meshes can be measured.
BakedScene bake_described_scene(const scene::SceneDescription& scene, const BakeOptions& options) {
  BakedScene baked;
  StageClock clock(baked, options);
  const BakeInputs in{scene, options, options.seed.value_or(scene.seed), std::max(1, options.jobs)};

  // What the scene asks must fit before anything is read or packed (scene_feasibility.hpp).
  scene::check_scene_amounts(scene);
  const Molecules molecules = clock.run("molecules", [&] { return load_molecules(scene); });

  std::vector<CompartmentBake> compartments(scene.compartments.size());
  for (std::size_t c = 0; c < compartments.size(); ++c)
    compartments[c].mesh = clock.run("meshes", [&] { return load_mesh(in, molecules, c); });
  const MeshMeasures measured = measure_meshes(compartments);
  check_nothing_emptied(scene, molecules.measures, molecules.patches, measured.measures,
                        [&](std::size_t c) -> const mesh::ProxyMesh& { return compartments[c].mesh.mesh; });
  check_placements(scene, molecules, measured);

  const std::vector<tiles::SurfaceDistortion> surfaces = plan_membranes(in, molecules, compartments);
  baked.estimate = estimate(in, molecules, compartments, measured);
  baked.cpu_seconds_at_estimate = process_cpu_seconds();
  if (options.max_memory && baked.estimate.peak_bytes > *options.max_memory)
    throw InputError(scene.source.string(), "", over_memory_budget(baked.estimate, *options.max_memory));
  if (options.estimate_only) return baked;

  const TileSets sets = clock.run("tile sets", [&] { return bake_tile_sets(in, molecules, surfaces); });
  summarise_tile_sets(baked, scene, sets, surfaces);

  // A compartment's core grid starts below its own membrane's shells (inner_height): each
  // compartment bakes its shells, then its core grid.
  for (std::size_t c = 0; c < compartments.size(); ++c) {
    CompartmentBake& bake = compartments[c];
    if (scene.compartments[c].membrane) {
      bake.membrane = clock.run("shells", [&] { return bake_shell(in, molecules, sets, c, bake); });
      bake.shell_margin = shell_margin(*bake.membrane);
    }
    if (scene.compartments[c].soluble)
      bake.core = clock.run("core grids", [&] { return bake_core_grid(in, molecules, sets, c, bake); });
  }

  std::vector<bool> sets_cached;
  for (const auto* group : {&sets.membrane, &sets.soluble})
    for (const BakedWangSet& set : *group) sets_cached.push_back(set.from_cache);
  const bool shells_cached =
      std::any_of(compartments.begin(), compartments.end(), [](const CompartmentBake& c) { return c.membrane && c.membrane->shells_from_cache; });
  if (shells_cached || std::find(sets_cached.begin(), sets_cached.end(), true) != sets_cached.end())
    baked.estimate_with_cache = estimate(in, molecules, compartments, measured, sets_cached);

  const std::vector<scene::PlacedInstance> placed =
      clock.run("instances", [&] { return place_instances(scene, compartments, measured); });
  std::optional<BakedMedium> medium;
  if (scene.medium) medium = clock.run("medium", [&] { return bake_scene_medium(in, molecules, sets, compartments, measured, placed); });
  clock.run("package content", [&] { fill_package_content(baked, {in, molecules, sets, compartments, medium}, placed); });
  check_every_molecule_placed(scene, baked);  // before anything is written (bake_invariants.hpp)
  baked.warnings = per_compartment_shortfalls(scene, baked);
  return baked;
}

}  // namespace

std::optional<double> compartment_bilayer_thickness(const scene::SceneDescription& scene, std::size_t c) {
  const auto& membrane = scene.compartments.at(c).membrane;
  if (!membrane) return std::nullopt;
  const scene::MembraneDescription& m = scene.membranes[membrane->index];
  std::vector<BakedMolecule> library;
  std::optional<BakedLipidPatch> patch;
  if (m.lipid_patch) {
    patch = load_lipid_patch(*m.lipid_patch, 0, library);
    for (const scene::LipidPatchDescription& species : m.lipid_mix) patch->mix.push_back(load_lipid_patch(species, 0, library));
  } else if (m.lipids) {
    // The fill's molecule at its library index, as membrane_bilayer_thickness reads it.
    library.resize(m.lipids->molecule.index + 1);
    library[m.lipids->molecule.index] = load_baked_molecule(scene.molecules[m.lipids->molecule.index], m.lipids->molecule.index);
  }
  return membrane_bilayer_thickness(m, patch, library);
}

double MembraneSummary::real_lipids_per_um2() const { return real_outer_per_um2 + real_inner_per_um2; }

namespace {
double share(double part, double whole) { return whole > 0.0 ? part / whole : 0.0; }
}  // namespace

MembraneSummary::ByLeaflet MembraneSummary::leaflet_areas() const {
  return {outer_area_um2 > 0.0 ? outer_area_um2 : area_um2, inner_area_um2 > 0.0 ? inner_area_um2 : area_um2};
}

MembraneSummary::ByLeaflet MembraneSummary::real_lipids_beside_proteins() const {
  const ByLeaflet area = leaflet_areas();
  return {std::max(0.0, area.outer - outer_protein_um2) * real_outer_per_um2,
          std::max(0.0, area.inner - inner_protein_um2) * real_inner_per_um2};
}

MembraneSummary::ByLeaflet MembraneSummary::fraction_of_real_leaflets_beside_proteins() const {
  const ByLeaflet real = real_lipids_beside_proteins();
  return {share(static_cast<double>(outer_lipids), real.outer), share(static_cast<double>(inner_lipids), real.inner)};
}

double MembraneSummary::fraction_of_real_bilayer_beside_proteins() const {
  const ByLeaflet real = real_lipids_beside_proteins();
  return share(static_cast<double>(outer_lipids + inner_lipids), real.outer + real.inner);
}

}  // namespace nano::scene_bake
