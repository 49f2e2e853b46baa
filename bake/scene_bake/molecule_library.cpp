#include "bake/scene_bake/molecule_library.hpp"

#include <cmath>

#include "bake/structure/structure_reader.hpp"

namespace nano::bake {

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

BakedMolecule load_baked_molecule(const scene::MoleculeDescription& description, std::size_t index) {
  structure::SelectionOptions options;
  options.all_models = description.all_models;
  options.keep_water = description.keep_water;
  options.keep_hydrogens = description.keep_hydrogens;
  structure::Molecule molecule = structure::read_molecule(description.file, options);

  BakedMolecule baked;
  baked.name = description.name;
  baked.source = description.file.filename().string();
  const structure::MoleculeProperties file_space =
      structure::compute_molecule_properties(molecule.atoms, description.up_axis);
  baked.atoms = std::move(molecule.atoms);
  for (structure::Atom& atom : baked.atoms) atom.position -= file_space.centroid;
  baked.properties = structure::compute_molecule_properties(baked.atoms, description.up_axis);
  baked.up = baked.properties.up;
  const glm::dvec3 srgb = description.colour.value_or(default_molecule_colour(index));
  baked.linear_colour = {srgb_to_linear(srgb.x), srgb_to_linear(srgb.y), srgb_to_linear(srgb.z)};
  return baked;
}

std::vector<BakedMolecule> load_molecule_library(const scene::SceneDescription& scene) {
  std::vector<BakedMolecule> library;
  library.reserve(scene.molecules.size());
  for (std::size_t i = 0; i < scene.molecules.size(); ++i)
    library.push_back(load_baked_molecule(scene.molecules[i], i));
  return library;
}

}  // namespace nano::bake
