#pragma once
// The scene's molecule types, read from their structure files and put into molecule space:
// origin at the centroid, so a rotation about the origin turns a molecule in place and the
// bounding radius about the origin is the tight one the tile packer and the shell sizes need.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "bake/scene/scene_description.hpp"
#include "bake/scene/scene_feasibility.hpp"
#include "bake/structure/atom.hpp"
#include "bake/structure/molecule_properties.hpp"

namespace nano::scene_bake {

struct BakedMolecule {
  std::string name;                         // the scene's name for the type
  std::string source;                       // structure file name, as provenance and for picking
  std::vector<structure::Atom> atoms;       // positions in molecule space (centroid at the origin)
  structure::MoleculeProperties properties; // computed in molecule space
  glm::dvec3 up{0.0, 0.0, 1.0};             // unit: the scene's axis, else the principal axis
  glm::dvec3 linear_colour{0.7};            // linear RGB in [0, 1]
};

// sRGB component in [0, 1] to linear light, as the package stores colours for shading.
double srgb_to_linear(double c);

// A distinct colour for type `index` when the scene names none (sRGB, deterministic).
glm::dvec3 default_molecule_colour(std::size_t index);

// Reads every molecule of the scene, in the scene's order. Throws InputError naming the
// structure file (and the scene key) for unreadable structures.
std::vector<BakedMolecule> load_molecule_library(const scene::SceneDescription& scene);

// A membrane's lipid patch: each lipid residue of the file appended to the library as its own type
// (molecule space at its centroid, up = +z, the file's orientation kept), with where the patch puts
// it: x, y in the file's frame, z from the bilayer mid-plane (the mean z of all lipid atoms).
struct BakedLipidPatch {
  std::vector<std::uint32_t> molecules;  // library indices, one per lipid
  std::vector<glm::dvec3> positions;     // of each lipid's centroid
  double period_x = 0.0, period_y = 0.0; // CRYST1 a, b (Å)
  double clearance = 0.6;
  double outer = 0.0, inner = 0.0;     // as a mixed species: the leaflets' fractions it takes
  std::vector<BakedLipidPatch> mix;    // other species laid in this patch's places
};

// Reads the patch (PDB with CRYST1 and alpha = beta = gamma = 90°; residues by chain, number and
// insertion code, waters dropped), appends its lipids to `library`. Throws InputError naming the
// file for a missing or skewed box, an mmCIF file or a patch without lipids.
BakedLipidPatch load_lipid_patch(const scene::LipidPatchDescription& patch, std::size_t colour_index,
                                 std::vector<BakedMolecule>& library);

// The patch's own lipids (its mixed species' too) by leaflet and kind: outer where a lipid's
// centroid stands at or above the mid-plane, as the tiles lay it.
std::pair<scene::LeafletCounts, scene::LeafletCounts> patch_leaflet_counts(const BakedLipidPatch& patch,
                                                                         const std::vector<BakedMolecule>& library);

// A stand-in's source, as the package stores it for pick and the bake summary:
// "stand-in (FROM, N spheres)"; is_stand_in_source tells one from a structure file's name.
inline constexpr std::string_view kStandInSourcePrefix = "stand-in (";
std::string stand_in_source(const std::string& from, std::size_t spheres);
bool is_stand_in_source(std::string_view source);

// One molecule from its description (exposed for tests): its structure file read, or its stand-in's
// spheres as pseudo-atoms.
BakedMolecule load_baked_molecule(const scene::MoleculeDescription& description, std::size_t index);

// The bilayer's thickness (Å): from its lowest to its highest atom surface across the patch and its
// mixed species, as laid (z from the mid-plane).
double bilayer_thickness(const BakedLipidPatch& patch, const std::vector<BakedMolecule>& library);

// The bilayer a membrane lines its meshes with (Å), which their shape is judged against: its lipid
// patch's, its lipid fill's (the lipid standing on both sides of the mid-plane at its offset), or,
// with neither, a POPC bilayer's (mesh::kDefaultBilayerThickness): proteins alone still stand in a
// membrane that thick.
double membrane_bilayer_thickness(const scene::MembraneDescription& membrane, const std::optional<BakedLipidPatch>& patch,
                                  const std::vector<BakedMolecule>& library);

}  // namespace nano::scene_bake
