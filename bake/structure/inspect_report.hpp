#pragma once
// What `nanobake inspect` prints, as JSON and as a human summary, built from one molecule.
#include <string>

#include <nlohmann/json.hpp>

#include "bake/structure/molecule_properties.hpp"
#include "bake/structure/structure_reader.hpp"

namespace nano::structure {

// Keys: file, format, atoms, models, chains (first-appearance order), elements (symbol -> count),
// hetatm_atoms, aabb and aabb_inflated ([[min],[max]]), centroid, radius, principal_axes,
// principal_variances, up, warnings.
nlohmann::json inspect_report_json(const Molecule& molecule, const MoleculeProperties& properties);

// The same facts as a few aligned lines of text, ending with a newline.
std::string inspect_report_text(const Molecule& molecule, const MoleculeProperties& properties);

}  // namespace nano::structure
