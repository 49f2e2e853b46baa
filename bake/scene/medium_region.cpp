#include "bake/scene/medium_region.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "bake/scene/transform.hpp"
#include "common/error.hpp"

namespace nano::scene {
namespace {

std::string angstrom(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.0f Å", v);
  return text;
}

std::string box_text(const Box& b) {
  char text[192];
  std::snprintf(text, sizeof text, "[[%.0f, %.0f, %.0f], [%.0f, %.0f, %.0f]]", b.min.x, b.min.y, b.min.z, b.max.x,
                b.max.y, b.max.z);
  return text;
}

Box sphere_bounds(std::span<const InstanceSphere> instances) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Box b{glm::dvec3(inf), glm::dvec3(-inf)};
  for (const InstanceSphere& s : instances) {
    b.min = glm::min(b.min, s.centre - s.radius);
    b.max = glm::max(b.max, s.centre + s.radius);
  }
  return b;
}

double distance_to_box(const glm::dvec3& p, const Box& b) {
  const glm::dvec3 outside = glm::max(glm::max(b.min - p, p - b.max), glm::dvec3(0.0));
  return std::sqrt(outside.x * outside.x + outside.y * outside.y + outside.z * outside.z);
}

// The key a user edits to change the region: the region itself, or the margin that derives it.
std::string region_key(const MediumDescription& m) { return m.region ? "medium.region" : "medium.margin"; }

}  // namespace

std::vector<InstanceSphere> instance_spheres(std::span<const PlacedInstance> placed,
                                             std::span<const double> bounding_radius) {
  std::vector<InstanceSphere> out;
  out.reserve(placed.size());
  for (const PlacedInstance& p : placed) {
    const glm::dvec3 centre(p.transform[0][3], p.transform[1][3], p.transform[2][3]);
    out.push_back({centre, bounding_radius[p.compartment.index] * largest_stretch(p.transform)});
  }
  return out;
}

double default_medium_margin(const SolubleDescription& medium) { return 2.0 * medium.cube_size; }

Box medium_region(const SceneDescription& scene, std::span<const InstanceSphere> instances) {
  const MediumDescription& m = scene.medium.value();
  if (m.region) return *m.region;
  const double margin = m.margin.value_or(default_medium_margin(scene.solubles.at(m.soluble.index)));
  Box b = sphere_bounds(instances);
  b.min -= margin;
  b.max += margin;
  return b;
}

void check_medium_region(const SceneDescription& scene, std::span<const MoleculeMeasure> molecules,
                         std::span<const InstanceSphere> instances) {
  if (!scene.medium) return;
  const MediumDescription& m = *scene.medium;
  const SolubleDescription& soluble = scene.solubles.at(m.soluble.index);
  const Box region = medium_region(scene, instances);
  const std::string file = scene.source.string();
  int complete = 1;
  for (int face = 0; face < 6; ++face) complete *= soluble.face_colours;
  if (soluble.cubes != complete)
    throw InputError(file, "solubles." + soluble.name + ".cubes",
                     std::to_string(soluble.cubes) + " cubes: the medium repeats one recipe through its region, which "
                     "needs the complete cube set of its " + std::to_string(soluble.face_colours) + " face colours (\"cubes\": " +
                         std::to_string(complete) + ")");

  double widest = 0;  // the largest diameter among the medium's molecules
  std::string widest_name;
  for (const SolubleMolecule& molecule : soluble.molecules) {
    const double d = 2.0 * molecules[molecule.molecule.index].bounding_radius;
    if (d > widest) widest = d, widest_name = molecule.molecule.name;
  }
  const glm::dvec3 size = region.max - region.min;
  const double narrowest = std::min({size.x, size.y, size.z});
  if (narrowest < widest + 2.0 * soluble.clearance)
    throw InputError(file, region_key(m),
                     "the medium's region " + box_text(region) + " is " + angstrom(narrowest) +
                         " across on its narrowest axis, less than one copy of '" + widest_name + "' (" +
                         angstrom(widest) + " across, plus " + angstrom(2.0 * soluble.clearance) + " of clearance" +
                         "): make it at least " + angstrom(std::ceil(widest + 2.0 * soluble.clearance)) + " on every axis");

  if (instances.empty()) return;
  double nearest = std::numeric_limits<double>::infinity();
  for (const InstanceSphere& s : instances) nearest = std::min(nearest, distance_to_box(s.centre, region) - s.radius);
  if (nearest > 0)
    throw InputError(file, region_key(m),
                     "the medium's region " + box_text(region) + " meets no compartment instance (the nearest is " +
                         angstrom(nearest) + " away; the instances lie within " + box_text(sphere_bounds(instances)) +
                         "): a medium fills the space between instances, so give a region that overlaps them, or "
                         "leave \"region\" out to surround them all");
}

}  // namespace nano::scene
