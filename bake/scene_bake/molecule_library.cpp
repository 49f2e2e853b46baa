#include "bake/scene_bake/molecule_library.hpp"
#include "bake/scene_bake/named_totals.hpp"

#include "bake/mesh/membrane_fit.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <glm/geometric.hpp>

#include "bake/structure/field_parsing.hpp"
#include "bake/structure/structure_reader.hpp"
#include "bake/structure/structure_text.hpp"
#include "common/error.hpp"

namespace nano::scene_bake {

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

glm::dvec3 default_molecule_colour(std::size_t index) {
  // Hues spaced by the golden angle stay distinct for any number of types.
  const double hue = std::fmod(0.08 + 0.61803398875 * static_cast<double>(index), 1.0);
  const double s = 0.55, v = 0.9;
  const double h6 = hue * 6.0;
  const double f = h6 - std::floor(h6);
  const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (static_cast<int>(h6) % 6) {
    case 0: return {v, t, p};
    case 1: return {q, v, p};
    case 2: return {p, v, t};
    case 3: return {p, q, v};
    case 4: return {t, p, v};
    default: return {v, p, q};
  }
}

namespace {

glm::dvec3 linear_colour(const glm::dvec3& srgb) {
  return {srgb_to_linear(srgb.x), srgb_to_linear(srgb.y), srgb_to_linear(srgb.z)};
}

// CRYST1 a, b of a PDB text; the box must be orthogonal (the patch repeats along x and y).
std::pair<double, double> patch_period(std::string_view text, const std::string& file) {
  std::istringstream lines{std::string(text)};
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("CRYST1", 0) != 0) continue;
    line.resize(std::max<std::size_t>(line.size(), 54), ' ');
    const auto a = structure::parse_real(line.substr(6, 9)), b = structure::parse_real(line.substr(15, 9));
    const auto alpha = structure::parse_real(line.substr(33, 7)), beta = structure::parse_real(line.substr(40, 7)),
               gamma = structure::parse_real(line.substr(47, 7));
    if (!a || !b || !(*a > 0) || !(*b > 0) || !std::isfinite(*a) || !std::isfinite(*b))
      throw InputError(file, "CRYST1", "the lipid patch's periodic box needs positive lengths a and b");
    for (const auto& angle : {alpha, beta, gamma})
      if (angle && std::abs(*angle - 90.0) > 1e-3)
        throw InputError(file, "CRYST1", "the lipid patch's periodic box must be orthogonal (angles of 90°)");
    return {*a, *b};
  }
  throw InputError(file, "CRYST1", "a lipid patch needs a CRYST1 record giving its periodic box");
}

}  // namespace

std::string stand_in_source(const std::string& from, std::size_t spheres) {
  return std::string(kStandInSourcePrefix) + from + ", " + std::to_string(spheres) + (spheres == 1 ? " sphere)" : " spheres)");
}

bool is_stand_in_source(std::string_view source) { return source.starts_with(kStandInSourcePrefix); }

namespace {

// A stand-in's spheres as the molecule's atoms: one pseudo-atom per sphere (no element, atom name SPH).
std::vector<structure::Atom> stand_in_atoms(const std::vector<glm::dvec4>& spheres) {
  std::vector<structure::Atom> atoms(spheres.size());
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    atoms[i].position = glm::dvec3(spheres[i]);
    atoms[i].radius = spheres[i].w;
    atoms[i].residue_name = "SPH";
    atoms[i].atom_name = "SPH";
    atoms[i].residue_number = static_cast<int>(i + 1);
  }
  return atoms;
}

}  // namespace

BakedMolecule load_baked_molecule(const scene::MoleculeDescription& description, std::size_t index) {
  BakedMolecule baked;
  baked.name = description.name;
  structure::Molecule molecule;
  if (description.stand_in_spheres.empty()) {
    structure::SelectionOptions options;
    options.all_models = description.all_models;
    options.keep_water = description.keep_water;
    options.keep_hydrogens = description.keep_hydrogens;
    molecule = structure::read_molecule(description.file, options);
    baked.source = description.file.filename().string();
  } else {
    molecule.atoms = stand_in_atoms(description.stand_in_spheres);
    baked.source = stand_in_source(description.stand_in_from, description.stand_in_spheres.size());
  }
  const structure::MoleculeProperties file_space =
      structure::compute_molecule_properties(molecule.atoms, description.up_axis);
  baked.atoms = std::move(molecule.atoms);
  for (structure::Atom& atom : baked.atoms) atom.position -= file_space.centroid;
  baked.properties = structure::compute_molecule_properties(baked.atoms, description.up_axis);
  baked.up = baked.properties.up;
  baked.linear_colour = linear_colour(description.colour.value_or(default_molecule_colour(index)));
  return baked;
}


namespace {

// The name and linear colour a patch lipid whose first atom is `first` reports under: the patch's,
// or its residue name's kind (each kind's default colour the next after the patch's index).
std::pair<std::string, glm::dvec3> lipid_kind(const scene::LipidPatchDescription& patch, const structure::Atom& first,
                                              std::size_t colour_index) {
  if (patch.kinds.empty())
    return {patch.name, linear_colour(patch.colour.value_or(default_molecule_colour(colour_index)))};
  for (std::size_t k = 0; k < patch.kinds.size(); ++k)
    if (patch.kinds[k].residue == first.residue_name)
      return {patch.kinds[k].name,
              linear_colour(patch.kinds[k].colour.value_or(default_molecule_colour(colour_index + k)))};
  std::string listed;
  for (const scene::LipidKind& kind : patch.kinds) listed += (listed.empty() ? "" : ", ") + kind.residue;
  throw InputError(patch.file.string(), "lipid_patch.kinds",
                   "residue " + first.residue_name + " " + std::to_string(first.residue_number) + " (chain " +
                       first.chain + ") is none of the kinds the scene lists (" + listed + ")");
}

}  // namespace

BakedLipidPatch load_lipid_patch(const scene::LipidPatchDescription& description, std::size_t colour_index,
                                 std::vector<BakedMolecule>& library) {
  const std::string file = description.file.string();
  const std::string text = structure::read_structure_text(description.file);
  if (structure::detect_structure_format(description.file, text) != structure::StructureFormat::Pdb)
    throw InputError(file, "lipid_patch", "a lipid patch must be a PDB file (its CRYST1 record gives the box)");
  BakedLipidPatch patch;
  std::tie(patch.period_x, patch.period_y) = patch_period(text, file);
  patch.clearance = description.clearance;
  const structure::Molecule molecule =
      structure::molecule_from_text(text, structure::StructureFormat::Pdb, file, structure::SelectionOptions{});

  double mid = 0.0;
  for (const structure::Atom& a : molecule.atoms) mid += a.position.z;
  mid /= static_cast<double>(molecule.atoms.size());
  const glm::dvec3 up(0.0, 0.0, 1.0);
  for (std::size_t begin = 0; begin < molecule.atoms.size();) {
    const structure::Atom& first = molecule.atoms[begin];
    std::size_t end = begin;
    while (end < molecule.atoms.size() && molecule.atoms[end].chain == first.chain &&
           molecule.atoms[end].residue_number == first.residue_number &&
           molecule.atoms[end].insertion_code == first.insertion_code)
      ++end;
    BakedMolecule lipid;
    std::tie(lipid.name, lipid.linear_colour) = lipid_kind(description, first, colour_index);
    lipid.source = description.file.filename().string();
    lipid.atoms.assign(molecule.atoms.begin() + begin, molecule.atoms.begin() + end);
    const glm::dvec3 centroid = structure::compute_molecule_properties(lipid.atoms, up).centroid;
    for (structure::Atom& atom : lipid.atoms) atom.position -= centroid;
    lipid.properties = structure::compute_molecule_properties(lipid.atoms, up);
    lipid.up = up;
    patch.molecules.push_back(static_cast<std::uint32_t>(library.size()));
    patch.positions.push_back(centroid - glm::dvec3(0.0, 0.0, mid));
    library.push_back(std::move(lipid));
    begin = end;
  }
  return patch;
}

std::pair<scene::LeafletCounts, scene::LeafletCounts> patch_leaflet_counts(const BakedLipidPatch& patch,
                                                                         const std::vector<BakedMolecule>& library) {
  std::pair<scene::LeafletCounts, scene::LeafletCounts> counts;
  const auto add = [&](const BakedLipidPatch& species) {
    for (std::size_t i = 0; i < species.molecules.size(); ++i)
      ++named_entry(species.positions[i].z >= 0.0 ? counts.first : counts.second, library[species.molecules[i]].name);
  };
  add(patch);
  for (const BakedLipidPatch& species : patch.mix) add(species);
  return counts;
}

std::vector<BakedMolecule> load_molecule_library(const scene::SceneDescription& scene) {
  std::vector<BakedMolecule> library;
  library.reserve(scene.molecules.size());
  for (std::size_t i = 0; i < scene.molecules.size(); ++i)
    library.push_back(load_baked_molecule(scene.molecules[i], i));
  return library;
}

double bilayer_thickness(const BakedLipidPatch& patch, const std::vector<BakedMolecule>& library) {
  double lo = INFINITY, hi = -INFINITY;
  auto extend = [&](const BakedLipidPatch& species) {
    for (std::size_t i = 0; i < species.molecules.size(); ++i)
      for (const structure::Atom& a : library.at(species.molecules[i]).atoms) {
        const double z = species.positions[i].z + a.position.z;
        lo = std::min(lo, z - a.radius);
        hi = std::max(hi, z + a.radius);
      }
  };
  extend(patch);
  for (const BakedLipidPatch& species : patch.mix) extend(species);
  return hi > lo ? hi - lo : 0.0;
}

double membrane_bilayer_thickness(const scene::MembraneDescription& membrane, const std::optional<BakedLipidPatch>& patch,
                                  const std::vector<BakedMolecule>& library) {
  if (patch) return bilayer_thickness(*patch, library);
  if (!membrane.lipids) return mesh::kDefaultBilayerThickness;
  // The outer copy stands up at +offset, the inner one mirrored at −offset.
  const BakedMolecule& lipid = library.at(membrane.lipids->molecule.index);
  double lo = INFINITY, hi = -INFINITY;
  for (const structure::Atom& a : lipid.atoms) {
    const double along = glm::dot(a.position, lipid.up);
    lo = std::min(lo, along - a.radius);
    hi = std::max(hi, along + a.radius);
  }
  const double offset = membrane.lipids->leaflet_offset;
  const double top = std::max(offset + hi, -(offset + lo));
  return hi > lo ? 2.0 * top : 0.0;
}

}  // namespace nano::scene_bake
