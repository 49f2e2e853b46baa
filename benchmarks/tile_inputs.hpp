#pragma once
// Tile-generator inputs shared by tiles_bench (which times generating them) and shell_bench (which
// needs a realistic set to compute offsets for). Built outside the timed loops.
#include <algorithm>
#include <string>

#include <glm/glm.hpp>

#include "benchmarks/bench_inputs.hpp"
#include "bake/structure/molecule_properties.hpp"
#include "bake/structure/structure_reader.hpp"
#include "bake/mesh/sphere_mesh.hpp"
#include "bake/mesh/uv_distortion.hpp"
#include "bake/mesh/vertex_normals.hpp"
#include "bake/tiles/wang_sets.hpp"

namespace nano::bench {

// Heavy atoms centred on their centroid with the principal axis as up (a membrane protein without
// an explicit "up" in the scene file), as bake/scene_bake/molecule_library.cpp prepares them;
// bounding_radius about the new origin, as the package stores it.
inline tiles::MoleculeType read_tile_molecule(const std::string& file, const std::string& name) {
  structure::SelectionOptions selection;
  selection.keep_hydrogens = false;
  const structure::Molecule molecule = structure::read_molecule(structure_path(file), selection);
  const structure::MoleculeProperties p = structure::compute_molecule_properties(molecule.atoms);
  tiles::MoleculeType type{name, {}, 0.f, glm::vec3(p.up)};
  double radius = 0.0;
  for (const structure::Atom& a : molecule.atoms) {
    const glm::dvec3 centre = a.position - p.centroid;
    type.atoms.push_back({glm::vec3(centre), static_cast<float>(a.radius)});
    radius = std::max(radius, glm::length(centre) + a.radius);
  }
  // Rounded up by a hair so float rounding never leaves an atom outside (MembraneMapping checks it).
  type.bounding_radius = static_cast<float>(radius * (1.0 + 1e-6));
  return type;
}

inline constexpr double kVirionRadius = 450.0;  // Å, data/virion.json's cube-sphere
inline constexpr int kVirionTriangles = 6000;

// The envelope of data/virion.json reduced to its most numerous protein, so one generation stays
// around a second: 16 squares (2 colours) of 200 Å, the M protein (qhd43419a) at the scene's
// 12,000 per µm² and a lipid_306 fill at 65 Å² per lipid per leaflet (±18 Å), seed 7.
inline tiles::MembraneTileRequest virion_membrane_request() {
  tiles::MembraneTileRequest request;
  request.types = {read_tile_molecule("qhd43419a.pdb", "membrane_protein_qhd43419a"),
                   read_tile_molecule("lipid_306.pdb", "lipid_306")};
  request.types[1].up_axis = {0.f, 0.f, 1.f};  // a lipid stands along the membrane normal
  request.edge = 200.f;
  request.colours = 2;
  request.molecules = {{0, 12000.0, 0.f}};
  request.lipids = tiles::LipidFill{1, 65.f, 18.f};
  // Packed to survive the virion's mesh, measured as bake/scene_bake/scene_baker.cpp does: the clash
  // rule's widened neighbour search is part of what generation costs on a curved membrane.
  const mesh::ProxyMesh virion = mesh::make_sphere_mesh(kVirionTriangles, kVirionRadius);
  request.surface = {static_cast<float>(mesh::chart_anisotropy(virion) - 1.0),
                     static_cast<float>(1.05 * mesh::normal_turn_rate(virion)),
                     static_cast<float>(mesh::largest_normal_tilt(virion)),
                     static_cast<float>(mesh::largest_facet_sag(virion))};
  request.seed = 7;
  return request;
}

}  // namespace nano::bench
