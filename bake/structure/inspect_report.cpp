#include "bake/structure/inspect_report.hpp"

#include <cstdio>
#include <map>
#include <unordered_set>
#include <vector>

namespace nano::structure {
namespace {

std::vector<std::string> chains_in_order(const Molecule& molecule) {
  std::vector<std::string> chains;
  std::unordered_set<std::string> seen;
  for (const Atom& atom : molecule.atoms)
    if (seen.insert(atom.chain).second) chains.push_back(atom.chain);
  return chains;
}

std::map<std::string, std::size_t> element_counts(const Molecule& molecule) {
  std::map<std::string, std::size_t> counts;
  for (const Atom& atom : molecule.atoms) ++counts[atom.element];
  return counts;
}

std::size_t hetatm_count(const Molecule& molecule) {
  std::size_t n = 0;
  for (const Atom& atom : molecule.atoms) n += atom.hetatm;
  return n;
}

nlohmann::json vec(const glm::dvec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

std::string format_vec(const glm::dvec3& v) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.3f, %.3f, %.3f)", v.x, v.y, v.z);
  return buffer;
}

}  // namespace

nlohmann::json inspect_report_json(const Molecule& molecule, const MoleculeProperties& p) {
  nlohmann::json j;
  j["file"] = molecule.source;
  j["format"] = molecule.format == StructureFormat::Mmcif ? "mmcif" : "pdb";
  j["atoms"] = molecule.atoms.size();
  j["hetatm_atoms"] = hetatm_count(molecule);
  j["models"] = molecule.model_count;
  j["chains"] = chains_in_order(molecule);
  j["elements"] = nlohmann::json::object();
  for (const auto& [element, count] : element_counts(molecule)) j["elements"][element] = count;
  j["aabb"] = nlohmann::json::array({vec(p.centres.min), vec(p.centres.max)});
  j["aabb_inflated"] = nlohmann::json::array({vec(p.spheres.min), vec(p.spheres.max)});
  j["centroid"] = vec(p.centroid);
  j["radius"] = p.bounding_radius;
  j["principal_axes"] = nlohmann::json::array({vec(p.principal_axes[0]), vec(p.principal_axes[1]), vec(p.principal_axes[2])});
  j["principal_variances"] = p.principal_variances;
  j["up"] = vec(p.up);
  j["warnings"] = molecule.warnings;
  return j;
}

std::string inspect_report_text(const Molecule& molecule, const MoleculeProperties& p) {
  std::string chains;
  for (const std::string& chain : chains_in_order(molecule)) chains += (chains.empty() ? "" : " ") + (chain.empty() ? "''" : chain);
  std::string elements;
  for (const auto& [element, count] : element_counts(molecule))
    elements += (elements.empty() ? "" : " ") + (element.empty() ? std::string("?") : element) + ":" + std::to_string(count);
  char buffer[256];
  std::string out;
  out += "file:       " + molecule.source + (molecule.format == StructureFormat::Mmcif ? " (mmCIF)\n" : " (PDB)\n");
  out += "atoms:      " + std::to_string(molecule.atoms.size()) + " (" + std::to_string(hetatm_count(molecule)) + " HETATM)\n";
  out += "models:     " + std::to_string(molecule.model_count) + "\n";
  out += "chains:     " + chains + "\n";
  out += "elements:   " + elements + "\n";
  out += "aabb:       " + format_vec(p.centres.min) + " .. " + format_vec(p.centres.max) + " (atom centres)\n";
  out += "            " + format_vec(p.spheres.min) + " .. " + format_vec(p.spheres.max) + " (with radii)\n";
  out += "centroid:   " + format_vec(p.centroid) + "\n";
  std::snprintf(buffer, sizeof buffer, "radius:     %.3f A (bounding sphere about the centroid)\n", p.bounding_radius);
  out += buffer;
  for (int i = 0; i < 3; ++i) {
    std::snprintf(buffer, sizeof buffer, "axis %d:     %s  variance %.3f A^2\n", i + 1, format_vec(p.principal_axes[i]).c_str(),
                  p.principal_variances[i]);
    out += buffer;
  }
  out += "up:         " + format_vec(p.up) + "\n";
  for (const std::string& warning : molecule.warnings) out += "warning:    " + warning + "\n";
  return out;
}

}  // namespace nano::structure
