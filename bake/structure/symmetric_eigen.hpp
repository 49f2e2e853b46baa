#pragma once
// Eigen-decomposition of a real symmetric 3x3 matrix by cyclic Jacobi rotations: slower than a
// closed form but accurate for repeated and tiny eigenvalues, which molecule covariances have.
#include <array>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace nano::structure {

struct SymmetricEigen {
  std::array<double, 3> values;        // descending
  std::array<glm::dvec3, 3> vectors;   // unit length, orthonormal, vectors[i] belongs to values[i]
};

// `m` must be symmetric (only its upper triangle is read). Eigenvectors have a deterministic
// sign: the component of largest magnitude is positive (the first one on ties).
SymmetricEigen symmetric_eigen(const glm::dmat3& m);

// Flips `v` so that its component of largest magnitude is positive (first one on ties).
glm::dvec3 canonical_sign(const glm::dvec3& v);

}  // namespace nano::structure
