#pragma once
// The measures of a scene's molecules that the feasibility checks
// (bake/scene/scene_feasibility.hpp) weigh the scene's amounts against: taken from the very atoms
// the packers will use, in milliseconds, before any tile is packed.
#include <vector>

#include "bake/scene/scene_description.hpp"
#include "bake/scene/scene_feasibility.hpp"
#include "bake/scene_bake/molecule_library.hpp"

namespace nano::scene_bake {

// One measure per scene.molecules entry (the library's first entries, in the scene's order). A
// membrane protein's leaflet footprints are taken at the depth of its first entry in a membrane.
std::vector<scene::MoleculeMeasure> measure_molecules(const scene::SceneDescription& scene,
                                                      const std::vector<BakedMolecule>& library);

// The volume of the union of the atoms' spheres (Å³), counted on a 0.5 Å grid (coarser for a
// molecule over 400 Å across): within 5 % for a single atom, closer for a protein's thousands.
double union_volume(const std::vector<structure::Atom>& atoms);

}  // namespace nano::scene_bake
