#pragma once
// Geometric summary of a molecule, as stored per molecule type in the package.
#include <array>
#include <optional>
#include <span>

#include <glm/vec3.hpp>

#include "bake/structure/atom.hpp"

namespace nano::structure {

struct Aabb {
  glm::dvec3 min{0.0}, max{0.0};
};

struct MoleculeProperties {
  Aabb centres;                              // box of atom centres
  Aabb spheres;                              // box of atom spheres (centres inflated by radii)
  glm::dvec3 centroid{0.0};                  // unweighted mean of centres
  double bounding_radius = 0.0;              // max |p - centroid| + r: a sphere about the centroid
  std::array<glm::dvec3, 3> principal_axes;  // covariance eigenvectors, largest variance first
  std::array<double, 3> principal_variances; // matching eigenvalues (Å²), descending
  glm::dvec3 up{0.0, 0.0, 1.0};              // given axis (normalised) or principal_axes[0]
};

// Requires at least one atom. `up` when given must be non-zero; it is normalised.
// Throws std::invalid_argument on an empty span or a zero `up`: a caller's bug, not bad input (the
// readers refuse a file whose selection leaves no atom; the scene's "up" and inspect's --up refuse
// the zero vector where they are read).
MoleculeProperties compute_molecule_properties(std::span<const Atom> atoms, std::optional<glm::dvec3> up = std::nullopt);

}  // namespace nano::structure
