#include "bake/scene_bake/molecule_measures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "bake/scene_bake/scene_baker.hpp"
#include "bake/scene_bake/wang_bake.hpp"
#include "bake/tiles/bilayer_footprint.hpp"
#include "bake/tiles/rotation_sampling.hpp"

namespace nano::scene_bake {
namespace {

// The finest grid cell (Å) for the union volume, coarsened so a large molecule needs at most
// kMaxVolumeCells cells.
constexpr double kVolumeCell = 0.5;
constexpr double kMaxVolumeCells = 6.4e7;

}  // namespace

double union_volume(const std::vector<structure::Atom>& atoms) {
  if (atoms.empty()) return 0.0;
  glm::dvec3 lo(atoms.front().position), hi(lo);
  for (const structure::Atom& a : atoms) {
    lo = glm::min(lo, a.position - a.radius);
    hi = glm::max(hi, a.position + a.radius);
  }
  const glm::dvec3 size = hi - lo;
  const double cell = std::max(kVolumeCell, std::cbrt(size.x * size.y * size.z / kMaxVolumeCells));
  const glm::ivec3 dims = glm::max(glm::ivec3(glm::ceil(size / cell)), glm::ivec3(1));
  std::vector<std::uint8_t> inside(static_cast<std::size_t>(dims.x) * dims.y * dims.z, 0);
  for (const structure::Atom& a : atoms) {
    // Cells whose centres lie within the sphere.
    const glm::ivec3 first = glm::max(glm::ivec3(glm::floor((a.position - a.radius - lo) / cell)), glm::ivec3(0));
    const glm::ivec3 last = glm::min(glm::ivec3(glm::floor((a.position + a.radius - lo) / cell)), dims - 1);
    const double r2 = a.radius * a.radius;
    for (int z = first.z; z <= last.z; ++z)
      for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x) {
          const glm::dvec3 centre = lo + (glm::dvec3(x, y, z) + 0.5) * cell;
          const glm::dvec3 d = centre - a.position;
          if (glm::dot(d, d) <= r2) inside[(static_cast<std::size_t>(z) * dims.y + y) * dims.x + x] = 1;
        }
  }
  const auto count = std::count(inside.begin(), inside.end(), std::uint8_t{1});
  return static_cast<double>(count) * cell * cell * cell;
}

std::vector<scene::MoleculeMeasure> measure_molecules(const scene::SceneDescription& scene,
                                                      const std::vector<BakedMolecule>& library) {
  std::vector<double> depth(scene.molecules.size(), 0.0);
  std::vector<char> in_membrane(scene.molecules.size(), 0);
  for (const scene::MembraneDescription& m : scene.membranes)
    for (const scene::MembraneProtein& p : m.proteins)
      if (!in_membrane[p.molecule.index]) {
        in_membrane[p.molecule.index] = 1;
        depth[p.molecule.index] = p.depth;
      }
  std::vector<scene::MoleculeMeasure> measures;
  for (std::size_t i = 0; i < scene.molecules.size(); ++i) {
    const BakedMolecule& molecule = library.at(i);
    scene::MoleculeMeasure m;
    m.bounding_radius = molecule.properties.bounding_radius;
    const glm::dvec3 up = glm::normalize(molecule.up);
    double below = 0.0, above = 0.0;
    for (const structure::Atom& a : molecule.atoms) {
      const double along = glm::dot(a.position, up);
      m.lateral_radius = std::max(m.lateral_radius, glm::length(a.position - along * up) + a.radius);
      below = std::min(below, along - a.radius);
      above = std::max(above, along + a.radius);
    }
    m.height = above - below;
    m.reach_below = -below;
    m.reach_above = above;
    m.volume = union_volume(molecule.atoms);
    if (in_membrane[i]) {
      // Standing as the membrane packer stands it: up along the normal, centre at its depth.
      const tiles::MoleculeType type = to_tile_molecule(molecule);
      tiles::Instance copy{0};
      copy.position = glm::vec3(0.f, 0.f, static_cast<float>(depth[i]));
      copy.rotation = tiles::rotation_between(type.up_axis, glm::vec3(0.f, 0.f, 1.f));
      m.outer_footprint = tiles::leaflet_footprint(type, copy, tiles::outer_leaflet(kLeafletHalfThickness), 0.5f);
      m.inner_footprint = tiles::leaflet_footprint(type, copy, tiles::inner_leaflet(kLeafletHalfThickness), 0.5f);
    }
    measures.push_back(m);
  }
  return measures;
}

}  // namespace nano::scene_bake
