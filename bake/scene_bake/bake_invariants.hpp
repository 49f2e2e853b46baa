#pragma once
// Nothing emptied, nothing detached (#39): a molecule a scene lists with a non-zero amount ends with
// copies in every compartment that wears its membrane or is filled with its soluble, or the bake is
// refused by the key of that amount, so that no package is written.
//
// Before the heavy stages, check_nothing_emptied runs the feasibility rules that need the molecules
// as read and the meshes as baked (after remeshing): room for each soluble inside each mesh, at
// least one expected copy per compartment, lipid-mix shares that take a place. After the package
// content, check_every_molecule_placed holds the bake to the promise by what it placed.
#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "bake/mesh/proxy_mesh.hpp"
#include "bake/scene/scene_description.hpp"
#include "bake/scene/scene_feasibility.hpp"
#include "bake/scene_bake/molecule_library.hpp"
#include "bake/scene_bake/scene_baker.hpp"

namespace nano::scene_bake {

// An upper bound on how far a point inside a closed mesh lies from its surface (Å): half the
// smallest side of its bounding box (a ray from the point along that axis leaves the mesh within
// it) and, when `enclosed_volume` > 0, the radius of a ball of that volume (a ball clear of the
// surface around a point inside lies wholly inside). 0 for a mesh without triangles.
double deepest_inside(const mesh::ProxyMesh& mesh, double enclosed_volume);

// A lipid patch's places per Wang square of edge `tile_size` in each leaflet, as its tiles lay it
// (wang_sets.cpp): the patch's lipids of that leaflet (centroid above the mid-plane: outer) times
// its repeats along each edge. At most: lipids that clash once the patch is rescaled are left out.
scene::PatchPlaces patch_places(const BakedLipidPatch& patch, double tile_size);

// scene::check_lipid_mix_amounts for every membrane with a patch (`patches` indexed like the
// scene's membranes), then scene::check_compartment_room for every compartment on its mesh as baked
// (`meshes[c]` its measure, `mesh_of(c)` the mesh, whose deepest point is bounded here).
void check_nothing_emptied(const scene::SceneDescription& scene, std::span<const scene::MoleculeMeasure> molecules,
                           const std::vector<std::optional<BakedLipidPatch>>& patches,
                           std::span<const scene::CompartmentMeasure> meshes,
                           const std::function<const mesh::ProxyMesh&(std::size_t)>& mesh_of);

// The end-of-bake invariant, on the bake's summaries (`baked.compartments` indexed like the scene's
// compartments, copies by molecule name; `baked.wang_sets` the membranes' sets, then the
// solubles'): every protein, lipid fill, lipid patch, lipid_mix species and soluble a compartment's
// membrane or soluble lists with a non-zero amount has at least one copy in that compartment.
// Otherwise an InputError naming the scene file, the key of that amount and what became of the
// copies (the set held none; all dropped where no prism fits or clashing; none inside the core).
void check_every_molecule_placed(const scene::SceneDescription& scene, const BakedScene& baked);

// A protein counted `per_compartment` that a compartment keeps fewer copies of than asked (its tiles
// placed too few to choose from): one sentence per shortfall, naming the amount's key, the
// compartment and both counts. Not refused (the count is an upper bound), but never silent.
std::vector<std::string> per_compartment_shortfalls(const scene::SceneDescription& scene, const BakedScene& baked);

}  // namespace nano::scene_bake
