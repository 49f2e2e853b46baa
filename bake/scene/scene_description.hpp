#pragma once
// scene.json as plain data (docs/scene.md). Named maps become vectors in the file's order, so
// everything baked from them is deterministic; a reference keeps both the name (for messages)
// and the index into its vector (for the baker). Lengths in Å, angles in degrees, times in s.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "bake/scene/transform.hpp"
#include "common/camera.hpp"
#include "common/effect_table.hpp"

namespace nano::scene {

inline constexpr const char* scene_format_marker = "nanouniverse-scene";
inline constexpr int scene_format_version = 1;

struct NameRef {
  std::string name;
  std::size_t index = 0;  // into the vector of the map the name belongs to
  bool operator==(const NameRef&) const = default;
};

struct Box {
  glm::dvec3 min{0.0};
  glm::dvec3 max{0.0};
  bool operator==(const Box&) const = default;
};

inline constexpr std::size_t kMaxStandInSpheres = 100'000;

struct MoleculeDescription {
  std::string name;
  std::filesystem::path file;          // resolved against the scene file's folder; empty for a stand-in
  std::optional<glm::dvec3> colour;    // sRGB components in [0, 1]; absent: the baker picks one
  std::optional<glm::dvec3> up_axis;   // unit vector; absent ("principal"): from the structure
  bool all_models = false;
  bool keep_water = false;
  bool keep_hydrogens = true;
  // A stand-in has no structure: the molecule is drawn as these spheres (centre xyz and radius w, Å,
  // in the molecule's own frame), e.g. the packing spheres of a cellPACK ingredient whose structure
  // is missing. `stand_in_from` says where they came from; both are shown wherever the molecule is.
  std::vector<glm::dvec4> stand_in_spheres;
  std::string stand_in_from;
  bool operator==(const MoleculeDescription&) const = default;
};

struct SurfaceAbundance {
  enum class Unit { per_um2, per_tile };
  Unit unit = Unit::per_um2;
  double value = 0.0;  // copies per µm² of membrane, or (average) copies per Wang tile
  bool operator==(const SurfaceAbundance&) const = default;
};

struct MembraneProtein {
  NameRef molecule;
  SurfaceAbundance abundance;
  double depth = 0.0;  // molecule centre along the outward membrane normal, Å
  // Copies each compartment wearing the membrane keeps (spread over its surface), the rest of
  // what the tiles place dropped; absent: every copy the tiles place.
  std::optional<std::uint64_t> per_compartment;
  bool operator==(const MembraneProtein&) const = default;
};

struct LipidFill {
  NameRef molecule;
  double area_per_lipid = 0.0;  // Å² per lipid in one leaflet
  double leaflet_offset = 0.0;  // distance of each leaflet's lipid centres from the mid-plane, Å
  bool operator==(const LipidFill&) const = default;
};

// One kind of lipid in a patch of several: the patch's residues named `residue` report under `name`.
struct LipidKind {
  std::string residue;               // residue name in the patch file (CHL1, POPC, PSM, ...)
  std::string name;                  // the name its copies, densities and picks report under
  std::optional<glm::dvec3> colour;  // sRGB; absent: the baker picks one
  bool operator==(const LipidKind&) const = default;
};

// What one leaflet of a patch is asked to hold: each kind's mole percent, and the mean area per
// molecule of a real leaflet of that composition (the reference a bake's lipid count is judged by).
struct LeafletComposition {
  std::vector<std::pair<std::string, double>> mol_percent;  // kind name -> mol %, adding up to 100
  double area_per_lipid = 0.0;                              // Å² per molecule
  bool operator==(const LeafletComposition&) const = default;
};

// A bilayer cut from an equilibrated periodic patch (a PDB file with CRYST1 a, b and the membrane
// normal along z): every lipid residue becomes its own molecule type (its own conformer), all named
// `name` and coloured alike, or, with `kinds`, named and coloured by their residue name.
struct LipidPatchDescription {
  std::string name = "lipid";
  std::filesystem::path file;        // resolved against the scene file's folder
  std::optional<glm::dvec3> colour;  // sRGB; absent: the baker picks one
  double clearance = 0.6;            // between two patch lipids: atoms stay >= clearance·(r1 + r2) apart
  // In "lipid_mix" only: the mole fractions of the outer leaflet (the side the mesh normals point
  // to) and of the inner one whose places take a conformer of this species instead of the base
  // patch's. Per leaflet the mix's fractions add up to at most 1; the base species keeps the rest.
  double outer = 0.0, inner = 0.0;
  std::vector<LipidKind> kinds;      // empty: one kind, `name`
  // The composition asked of each leaflet (the outer one faces the mesh normals, the patch's +z);
  // the bake is refused where a kind's share strays more than kLeafletShareTolerance from it.
  std::optional<LeafletComposition> outer_leaflet, inner_leaflet;
  bool operator==(const LipidPatchDescription&) const = default;
};

// How far (mole percent) a kind's share of its leaflet may stray from the share asked, in the patch
// and among the copies a bake keeps.
inline constexpr double kLeafletShareTolerance = 5.0;

struct MembraneDescription {
  std::string name;
  double tile_size = 0.0;  // edge of a Wang square, Å
  int edge_colours = 2;
  int tiles = 16;
  std::vector<MembraneProtein> proteins;
  std::optional<LipidFill> lipids;
  std::optional<LipidPatchDescription> lipid_patch;  // instead of `lipids`, never with it
  std::vector<LipidPatchDescription> lipid_mix;      // other species laid in the patch's places
  bool operator==(const MembraneDescription&) const = default;
};

struct VolumeAbundance {
  enum class Unit { millimolar, per_um3 };
  Unit unit = Unit::millimolar;
  double value = 0.0;
  bool operator==(const VolumeAbundance&) const = default;
};

struct SolubleMolecule {
  NameRef molecule;
  VolumeAbundance abundance;
  bool operator==(const SolubleMolecule&) const = default;
};

struct SolubleDescription {
  std::string name;
  double cube_size = 0.0;  // edge of a Wang cube, Å
  int face_colours = 2;
  int cubes = 16;
  std::vector<SolubleMolecule> molecules;
  double clearance = 0.0;  // gap kept between solubles and the membrane shell, Å
  bool operator==(const SolubleDescription&) const = default;
};

// The medium between the compartment instances (blood's plasma): a soluble that fills `region`, or
// the instances' bounding box grown by `margin`, everywhere outside every instance's membrane shell
// and interior, virtually (a periodic Wang-cube recipe, no storage per cube of the region).
struct MediumDescription {
  NameRef soluble;            // into SceneDescription::solubles
  std::optional<Box> region;  // world Å; absent: the instances' bounds grown by `margin`
  std::optional<double> margin;  // Å; absent (and no region): two cube edges of the soluble
  bool operator==(const MediumDescription&) const = default;
};

struct MeshSource {
  enum class Kind { file, sphere, rbc, box };
  // UVs: kept when the mesh has usable ones, made by the baker otherwise (automatic); or always
  // kept (a mesh without usable UVs is refused); or always made (bake/mesh/uv_charts.hpp).
  enum class Uv { automatic, keep, generate };
  Kind kind = Kind::file;
  std::filesystem::path file;  // Kind::file, resolved against the scene file's folder
  int triangles = 0;           // generated meshes: target triangle count
  double radius = 0.0;         // Kind::sphere, Å
  double unit = 1.0;           // Å per file unit ("units": "A" 1, "nm" 10, "um" 10^4); files only
  // At most one: the mesh scaled uniformly so its largest bounding-box side, or its enclosed
  // volume, becomes this (Å, Å^3), after the units.
  std::optional<double> diameter, volume;
  Uv uv = Uv::automatic;
  bool repair = false;  // mend what CGAL can (bake/mesh/mesh_repair.hpp) before the checks
  // Remeshing for a membrane (bake/mesh/mesh_remesh.hpp): when creases need it (automatic), never
  // (off), or always to the scene's edge (Å).
  enum class Remesh { automatic, off, edge };
  Remesh remesh = Remesh::automatic;
  double remesh_edge = 0.0;  // Remesh::edge
  glm::dvec3 box_size{0.0};  // Kind::box: its sides, Å (centred on the compartment's origin)
  bool operator==(const MeshSource&) const = default;
};

struct CompartmentDescription {
  std::string name;
  MeshSource mesh;
  std::optional<NameRef> membrane;  // into SceneDescription::membranes
  std::optional<NameRef> soluble;   // into SceneDescription::solubles
  double scale = 1.0;               // applied to the mesh: compartment space = scale × mesh space
  bool operator==(const CompartmentDescription&) const = default;
};

struct ExplicitInstance {
  NameRef compartment;
  Matrix3x4 transform = identity_transform();  // compartment space -> world
  bool operator==(const ExplicitInstance&) const = default;
};

// Expanded into `count` explicit instances by expand_random_instances().
struct RandomPlacement {
  NameRef compartment;
  int count = 0;
  Box box;                 // every placed bounding sphere lies inside
  std::uint64_t seed = 0;  // given, or derived from the scene seed and the entry's index
  double min_gap = 0.0;    // least distance between bounding spheres, Å
  bool operator==(const RandomPlacement&) const = default;
};

using InstanceEntry = std::variant<ExplicitInstance, RandomPlacement>;

struct Clipping {
  std::vector<glm::dvec4> planes;  // unit normal n and d: points with n·p + d >= 0 stay visible
  std::optional<Box> box;          // only points inside stay visible
  bool operator==(const Clipping&) const = default;
};

// Every instance spins about its own origin and drifts at a constant velocity.
struct SteadyMotion {
  glm::dvec3 spin_axis{0.0, 0.0, 1.0};  // unit
  double spin_degrees_per_second = 0.0;
  glm::dvec3 velocity{0.0};  // Å per second
  bool operator==(const SteadyMotion&) const = default;
};

struct Keyframe {
  double time = 0.0;                           // seconds, strictly increasing per instance
  Matrix3x4 transform = identity_transform();  // replaces the instance's transform at `time`
  bool operator==(const Keyframe&) const = default;
};

struct InstanceKeyframes {
  std::size_t instance = 0;  // index into the expanded instance list
  std::vector<Keyframe> keys;
  bool operator==(const InstanceKeyframes&) const = default;
};

// Proxy motion: "effects.animation" without its jitter, which is a plain effect of the table.
struct Animation {
  std::optional<SteadyMotion> steady;       // at most one of steady and keyframes is used
  std::vector<InstanceKeyframes> keyframes;
  bool moves() const { return steady.has_value() || !keyframes.empty(); }
  bool operator==(const Animation&) const = default;
};

// Each absent effect is off. Clipping and proxy motion are structured; every other effect is a row
// of common/effect_table.hpp, on when the scene sets it, its parameters at their slots of the
// package's effects record, as the baker writes it.
struct Effects {
  std::optional<Clipping> clipping;
  std::optional<Animation> animation;
  std::array<bool, kEffectCount> plain{};  // the table's effects the scene sets
  gpu::SceneEffects parameters{};          // their parameters; every other member zero
  bool sets(EffectId id) const { return plain[static_cast<std::size_t>(id)]; }
  bool operator==(const Effects&) const = default;
};

struct SceneDescription {
  std::filesystem::path source;  // the scene file, for messages
  std::uint64_t seed = 0;
  std::vector<MoleculeDescription> molecules;
  std::vector<MembraneDescription> membranes;
  std::vector<SolubleDescription> solubles;
  std::vector<CompartmentDescription> compartments;
  std::vector<InstanceEntry> instances;
  std::optional<MediumDescription> medium;
  Effects effects;
  std::optional<Camera> camera;  // absent: derived from the scene bounds by the baker
  bool operator==(const SceneDescription&) const = default;
};

// Instances after random placement is expanded, in the order of SceneDescription::instances.
struct PlacedInstance {
  NameRef compartment;
  Matrix3x4 transform;
  bool operator==(const PlacedInstance&) const = default;
};

}  // namespace nano::scene
