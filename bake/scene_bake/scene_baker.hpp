#pragma once
// nanobake's pipeline, in the stages the bake report times: molecules -> meshes -> (the estimate)
// -> tile sets -> per compartment shells, core grids -> instances -> package content.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bake/scene/scene_description.hpp"
#include "bake/scene_bake/bake_estimate.hpp"
#include "bake/scene_bake/medium_bake.hpp"
#include "bake/scene_bake/package_content.hpp"

#include "bake/mesh/mesh_remesh.hpp"
#include "bake/mesh/mesh_repair.hpp"
#include "bake/mesh/uv_charts.hpp"

namespace nano::scene_bake {

// How the package stores its meshes: Draco where smaller than zstd (the meshes baked on Draco's exact
// grids), Draco always (an error if it cannot), or zstd with the meshes exactly as read.
enum class MeshCodec { automatic, draco, zstd };

struct BakeOptions {
  std::optional<std::uint64_t> seed;  // overrides the scene's seed
  MeshCodec mesh_codec = MeshCodec::automatic;
  int jobs = 1;                       // worker threads for the heavy stages
  // Stage announcements (each may be empty): a stage begins; it ended after `seconds`.
  std::function<void(const std::string& stage)> on_stage_begin;
  std::function<void(const std::string& stage, double seconds)> on_stage_end;
  // Refuse, before the heavy stages, a bake whose estimated peak memory passes this (bytes).
  std::optional<double> max_memory;
  bool estimate_only = false;  // stop after the estimate (--dry-run): BakedScene holds only it
  // Where the shells stage is kept between bakes (shell_cache.hpp); absent: always computed.
  std::optional<std::filesystem::path> cache_directory;
};

// The bilayer the bake lines compartment `c` of `scene` with (molecule_library.hpp:
// membrane_bilayer_thickness), nullopt when it has no membrane; reads the membrane's lipids only.
std::optional<double> compartment_bilayer_thickness(const scene::SceneDescription& scene, std::size_t c);

// A real bilayer's lipids per µm² of membrane: two leaflets of one lipid per ~0.66 nm²
// (phosphatidylcholine; BIOLOGY.md section 1.4 cross-checks 0.5 nm² with cholesterol mixed in).
inline constexpr double kRealBilayerLipidsPerUm2 = 2.0 / 0.66e-6;

// What a compartment's membrane holds per area, as a structural biologist would count it.
struct MembraneSummary {
  struct ByLeaflet {
    double outer = 0.0, inner = 0.0;
  };
  double area_um2 = 0.0;                                               // the mesh's surface
  std::vector<std::pair<std::string, std::uint64_t>> lipids;           // species -> kept copies
  std::vector<std::pair<std::string, std::uint64_t>> dropped;          // molecule -> copies dropped (clashing, or beyond a count)
  std::vector<std::pair<std::string, std::uint64_t>> alternates;       // molecule -> alternates shown where a copy was dropped
  std::vector<std::pair<std::string, std::uint64_t>> unfit;            // molecule -> proteins left out where no prism held them
  bool pruned_everywhere = false;                                      // else along UV seams and on checked triangles
  std::uint64_t checked_copies = 0, atom_pairs = 0, copy_pairs_tested = 0;
  std::uint64_t checked_triangles = 0, triangles = 0;  // triangles whose copies were all checked, of all
  std::uint64_t outer_lipids = 0, inner_lipids = 0;  // by leaflet (the outer one faces the mesh normals)
  scene::LeafletCounts outer_kinds, inner_kinds;     // the same by kind (a "lipids" fill: counted outer)
  // A real bilayer's lipids per µm² in each leaflet: of the composition the patch's leaflets ask
  // (their area_per_lipid), else of phosphatidylcholine (half kRealBilayerLipidsPerUm2 each).
  double real_outer_per_um2 = 0.0, real_inner_per_um2 = 0.0;
  // Leaflet area the kept proteins take (tiles::leaflet_footprint within kLeafletHalfThickness of
  // the mid-plane), µm²: a real bilayer holds its lipids in the rest.
  double outer_protein_um2 = 0.0, inner_protein_um2 = 0.0;
  // Each leaflet's own surface, µm²: the mesh moved along its normals to where the leaflet's lipid
  // centres stand (mesh::offset_surface_area), so that a leaflet on a curved membrane is held against
  // a real one of its own area (0: the mesh's, as for a lipid fill).
  double outer_area_um2 = 0.0, inner_area_um2 = 0.0;
  ByLeaflet leaflet_areas() const;

  // Lipids against a real bilayer's count in the area the proteins leave: both leaflets, and each
  // leaflet against a real one of its own composition in the area its proteins leave.
  double fraction_of_real_bilayer_beside_proteins() const;
  ByLeaflet real_lipids_beside_proteins() const;  // a real leaflet's count in the area its proteins leave
  ByLeaflet fraction_of_real_leaflets_beside_proteins() const;
  double real_lipids_per_um2() const;  // both leaflets
};

// Phosphate to mid-plane of a POPC leaflet (~19.5 Å): where a protein's atoms take lipid room.
inline constexpr float kLeafletHalfThickness = 20.f;

struct CompartmentSummary {
  std::optional<MembraneSummary> membrane;
  std::string name;
  std::string mesh_origin;
  double mesh_scale = 1.0;                      // compartment space per mesh unit
  std::string uv_origin;                        // from the mesh, or why the baker made them
  std::string mesh_storage;                     // on Draco's grids, or why exact (CompartmentMesh::storage)
  double bilayer_thickness = 0.0;               // Å, the membrane's (0: no membrane); check-mesh --bilayer
  double thinnest_wall = 0.0;                   // Å, the mesh's, where the membrane lines it
  std::optional<mesh::ChartAtlas> charts;       // the charts the baker made
  std::optional<mesh::RepairReport> repair;     // what "repair" changed
  std::optional<mesh::RemeshReport> remesh;     // what remeshing for the membrane changed
  std::uint32_t triangles = 0;
  std::uint64_t represented_atoms = 0;  // one copy of the compartment
  std::vector<std::pair<std::string, std::uint64_t>> copies;  // molecule name -> copies (one compartment)
  std::uint64_t core_boxes_inside = 0, core_boxes_boundary = 0;
  std::uint32_t replication_width = 0, replication_height = 0;
  bool shells_from_cache = false;  // its shells stage read from the bake cache
};

struct InstanceSummary {
  std::string compartment;
  glm::dvec3 aabb_min{0.0}, aabb_max{0.0};  // world
};

struct WangSetSummary {
  std::string name;  // membrane or soluble name
  std::vector<tiles::MoleculeDensity> densities;
  std::optional<tiles::SurfaceDistortion> surface;  // membranes only: what the tiles were packed to survive
  bool from_cache = false;  // read from the bake cache (tile_set_cache.hpp), not packed
};

// The medium as the report gives it: region, what it holds (estimated by volume, medium_bake.hpp)
// and the exclusion field of each compartment.
struct MediumSummary {
  std::string soluble;
  glm::dvec3 region_min{0.0}, region_max{0.0};
  glm::uvec3 boxes{0};
  double copies_in_region = 0.0;  // before exclusion
  std::vector<MediumMoleculeCount> counts;
  struct Field {
    std::string compartment;
    double spacing = 0.0, margin = 0.0, measured_excess = 0.0;
    double least_reach = 0.0, largest_reach = 0.0;  // how far its membrane's copies reach from their triangles
    std::size_t bytes = 0;
  };
  std::vector<Field> fields;
};

struct BakedScene {
  PackageContent content;
  std::optional<MediumSummary> medium;
  std::vector<CompartmentSummary> compartments;
  std::vector<InstanceSummary> instances;
  std::vector<WangSetSummary> wang_sets;
  std::uint64_t represented_atoms = 0;  // the whole scene
  std::vector<std::pair<std::string, double>> stage_seconds;
  std::vector<std::pair<std::string, double>> stage_cpu_seconds;  // every thread's
  std::vector<std::pair<std::string, double>> stage_peak_bytes;   // the process's peak memory when each ended
  BakeEstimate estimate;  // made before the heavy stages
  // The same estimate once the bake cache served some compartments' shells (their checking not
  // counted): what the stages after the estimate are to be held against. Absent: none did.
  std::optional<BakeEstimate> estimate_with_cache;
  double cpu_seconds_at_estimate = 0.0;  // process_cpu_seconds() then: what came after is what was estimated
  std::vector<std::string> warnings;     // what the bake kept short of the scene's asking, by key (bake_invariants.hpp)
};

BakedScene bake_scene(const scene::SceneDescription& scene, const BakeOptions& options);

}  // namespace nano::scene_bake
