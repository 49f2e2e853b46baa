// libFuzzer target: arbitrary bytes through the strict JSON reader, the scene parser, the
// feasibility checks (with molecule and mesh measures made up from the names, as the baker would
// measure them) and, for scenes that pass, random instance placement. Rejection as an InputError is
// the expected outcome; anything else (another exception, a crash, a sanitizer report, a parsed
// scene holding a non-finite number or a non-unit axis, a hang, an allocation over -rss_limit_mb)
// is a finding. fuzz_scene is nano_fuzzer's reader "scene" (fuzz_main.cpp).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <glm/geometric.hpp>

#include "common/json_document.hpp"
#include "bake/scene/random_placement.hpp"
#include "bake/scene/scene_feasibility.hpp"
#include "bake/scene/scene_parser.hpp"
#include "common/error.hpp"

namespace {

using namespace nano;
using namespace nano::scene;

// Placing more copies than this is left out: the scene is valid, but each run would take long
// enough to slow the search to a crawl (the placement is covered up to this many; the seed
// mixed-sizes.json places 19001, 0.5 s here, and took over 10 s while one grid held all sizes).
constexpr std::size_t kMaxCopiesPlaced = 20'000;

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "scene fuzzer: %s\n", what.c_str());
  std::abort();
}

// FNV-1a: measures that depend on the name only, so a scene gets the same ones every run.
std::uint64_t hash_of(std::string_view s, std::uint64_t salt) {
  std::uint64_t h = 0xcbf29ce484222325ull ^ salt;
  for (const unsigned char c : s) h = (h ^ c) * 0x100000001b3ull;
  return h ^ (h >> 29);
}

// A fraction in [0, 1) from 16 bits of `h`.
double fraction(std::uint64_t h, int which) { return static_cast<double>((h >> (16 * which)) & 0xffff) / 65536.0; }

// Realistic molecules: a lipid 8 to 15 Å in reach, a protein 10 to 60 Å (haemoglobin is 30), and
// one molecule in eight anywhere from 5 to 200 Å (a large complex), so that the checks both pass
// and refuse. A few are degenerate in the ways a measure can be (no footprint in a leaflet, no
// height).
MoleculeMeasure measure_molecule(const MoleculeDescription& m, bool lipid) {
  const std::uint64_t h = hash_of(m.name, 1);
  MoleculeMeasure out;
  const double f = fraction(h, 0);
  if (h % 8 == 0) out.bounding_radius = 5.0 * std::pow(40.0, f);
  else out.bounding_radius = lipid ? 8.0 + 7.0 * f : 10.0 * std::pow(6.0, f);
  out.lateral_radius = out.bounding_radius * (lipid ? 0.25 + 0.25 * fraction(h, 1) : 0.4 + 0.6 * fraction(h, 1));
  out.height = 2.0 * out.bounding_radius * (0.5 + 0.5 * fraction(h, 2));
  out.volume = 4.0 / 3.0 * std::numbers::pi * std::pow(out.bounding_radius, 3) * (0.2 + 0.4 * fraction(h, 3));
  if (lipid && h % 8 != 0) {  // POPC: about 1250 Å³ over 2 x 12 Å
    out.height = 20.0 + 10.0 * fraction(h, 2);
    out.volume = 900.0 + 600.0 * fraction(h, 3);
  }
  const double disc = std::numbers::pi * out.lateral_radius * out.lateral_radius;
  const std::uint64_t g = hash_of(m.name, 2);
  out.outer_footprint = std::min(20000.0, disc * fraction(g, 0));
  out.inner_footprint = std::min(20000.0, disc * fraction(g, 1));
  switch (g >> 60) {
    case 0: out.outer_footprint = out.inner_footprint = 0.0; break;  // stands outside the bilayer
    case 1: out.height = 0.0; break;                                  // flat
    default: break;
  }
  return out;
}

// The mesh as the description sizes it (a file mesh gets a size from its name): 100 Å to 2e6 Å,
// so that both sides of the float-precision bound are reached.
CompartmentMeasure measure_compartment(const SceneDescription& scene, const CompartmentDescription& c) {
  const std::uint64_t h = hash_of(c.name, 3);
  double extent = 0.0;
  if (c.mesh.diameter) extent = 0.5 * *c.mesh.diameter;
  else if (c.mesh.volume) extent = std::cbrt(*c.mesh.volume * 3.0 / (4.0 * std::numbers::pi));
  else if (c.mesh.kind == MeshSource::Kind::sphere) extent = c.mesh.radius * c.scale;
  else if (c.mesh.kind == MeshSource::Kind::rbc) extent = 39100.0 * c.scale;
  else extent = 100.0 * std::pow(2e4, fraction(h, 0)) * c.scale;
  CompartmentMeasure out;
  out.extent = extent;
  out.area = 4.0 * std::numbers::pi * extent * extent * (0.4 + 0.6 * fraction(h, 1));
  out.volume = 4.0 / 3.0 * std::numbers::pi * extent * extent * extent * (0.2 + 0.8 * fraction(h, 2));
  const std::size_t file_triangles = h % 4 == 0 ? 4 + (h >> 41) : 4 + (h >> 47);  // up to 8e6, or to 1.3e5
  out.triangles = c.mesh.kind == MeshSource::Kind::file ? file_triangles : static_cast<std::size_t>(c.mesh.triangles);
  if (c.membrane) out.bilayer_thickness = 30.0 + 40.0 * fraction(hash_of(scene.membranes.at(c.membrane->index).name, 4), 0);
  return out;
}

// What the parser promises about a scene it accepts.
void check_finite(double v, const char* what) {
  if (!std::isfinite(v)) finding(std::string("accepted scene holds a non-finite ") + what);
}
void check_finite(const glm::dvec3& v, const char* what) {
  for (int i = 0; i < 3; ++i) check_finite(v[i], what);
}
void check_unit(const glm::dvec3& v, const char* what) {
  check_finite(v, what);
  if (std::abs(glm::dot(v, v) - 1.0) > 1e-9) finding(std::string("accepted scene holds a non-unit ") + what);
}
void check_finite(const Matrix3x4& m, const char* what) {
  for (const glm::dvec4& row : m)
    for (int i = 0; i < 4; ++i) check_finite(row[i], what);
}

void check_parsed(const SceneDescription& s) {
  for (const MoleculeDescription& m : s.molecules)
    if (m.up_axis) check_unit(*m.up_axis, "molecule up axis");
  for (const InstanceEntry& e : s.instances) {
    if (const auto* fixed = std::get_if<ExplicitInstance>(&e)) check_finite(fixed->transform, "instance transform");
  }
  if (s.effects.clipping)
    for (const glm::dvec4& p : s.effects.clipping->planes) {
      check_unit(glm::dvec3(p), "clipping plane normal");
      check_finite(p.w, "clipping plane offset");
    }
  if (s.effects.animation) {
    if (s.effects.animation->steady) check_unit(s.effects.animation->steady->spin_axis, "spin axis");
    for (const InstanceKeyframes& k : s.effects.animation->keyframes)
      for (const Keyframe& key : k.keys) check_finite(key.transform, "keyframe transform");
  }
  if (s.effects.sets(EffectId::shadows)) {
    // Held as the package holds it, a float vec3: unit to within a float's rounding.
    const glm::dvec3 light(direction_slot(s.effects.parameters, effect_parameter(EffectId::shadows, "light_direction")));
    if (!(std::abs(glm::length(light) - 1.0) <= 1e-6)) finding("accepted scene holds a non-unit light direction");
  }
  if (s.camera) check_unit(s.camera->up, "camera up");
}

void run(std::string_view text) {
  const SceneDescription scene = parse_scene_description(parse_json_text(text, "fuzz.json"), "fuzz/scene.json");
  check_parsed(scene);
  check_scene_amounts(scene);

  std::vector<bool> lipid(scene.molecules.size(), false);
  for (const MembraneDescription& m : scene.membranes)
    if (m.lipids) lipid[m.lipids->molecule.index] = true;
  std::vector<MoleculeMeasure> molecules;
  for (std::size_t i = 0; i < scene.molecules.size(); ++i) molecules.push_back(measure_molecule(scene.molecules[i], lipid[i]));
  check_molecule_amounts(scene, molecules);

  std::vector<double> radii;  // bounding radius about the origin, shell included
  for (std::size_t c = 0; c < scene.compartments.size(); ++c) {
    const CompartmentMeasure mesh = measure_compartment(scene, scene.compartments[c]);
    check_compartment_amounts(scene, c, mesh, molecules);
    radii.push_back(mesh.extent + mesh.bilayer_thickness);
  }
  check_placement_amounts(scene, radii);
  if (expanded_instance_count(scene) > kMaxCopiesPlaced) return;
  const std::vector<PlacedInstance> placed = expand_random_instances(scene, radii);
  if (placed.size() != expanded_instance_count(scene)) finding("expand_random_instances placed the wrong number of copies");
  for (const PlacedInstance& p : placed) check_finite(p.transform, "placed transform");
}

}  // namespace

namespace nano::fuzz {

void fuzz_scene(std::span<const std::byte> bytes) {
  try {
    run(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  } catch (const InputError&) {
  }
}

}  // namespace nano::fuzz
