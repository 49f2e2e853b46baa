#include "bake/structure/molecule_properties.hpp"

#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "bake/structure/symmetric_eigen.hpp"

namespace nano::structure {

MoleculeProperties compute_molecule_properties(std::span<const Atom> atoms, std::optional<glm::dvec3> up) {
  if (atoms.empty()) throw std::invalid_argument("compute_molecule_properties: no atoms");
  if (up && glm::length(*up) == 0.0) throw std::invalid_argument("compute_molecule_properties: zero up axis");
  MoleculeProperties p;
  p.centres = {atoms[0].position, atoms[0].position};
  p.spheres = {atoms[0].position - atoms[0].radius, atoms[0].position + atoms[0].radius};
  glm::dvec3 sum{0.0};
  for (const Atom& atom : atoms) {
    sum += atom.position;
    p.centres.min = glm::min(p.centres.min, atom.position);
    p.centres.max = glm::max(p.centres.max, atom.position);
    p.spheres.min = glm::min(p.spheres.min, atom.position - atom.radius);
    p.spheres.max = glm::max(p.spheres.max, atom.position + atom.radius);
  }
  const double n = static_cast<double>(atoms.size());
  p.centroid = sum / n;

  // Second pass about the centroid: summing raw squares would cancel catastrophically for
  // molecules far from the origin.
  glm::dmat3 covariance(0.0);
  for (const Atom& atom : atoms) {
    const glm::dvec3 d = atom.position - p.centroid;
    p.bounding_radius = std::max(p.bounding_radius, glm::length(d) + atom.radius);
    for (int r = 0; r < 3; ++r)
      for (int c = r; c < 3; ++c) covariance[c][r] += d[r] * d[c];
  }
  covariance /= n;
  const SymmetricEigen eigen = symmetric_eigen(covariance);
  p.principal_axes = eigen.vectors;
  p.principal_variances = eigen.values;
  p.up = up ? glm::normalize(*up) : eigen.vectors[0];
  return p;
}

}  // namespace nano::structure
