#include "bake/structure/molecule_properties.hpp"
#include "bake/structure/symmetric_eigen.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace nano::structure {
namespace {

glm::dmat3 symmetric(double a00, double a01, double a02, double a11, double a12, double a22) {
  glm::dmat3 m;  // glm: m[column][row]
  m[0] = {a00, a01, a02};
  m[1] = {a01, a11, a12};
  m[2] = {a02, a12, a22};
  return m;
}

void expect_eigenpairs(const glm::dmat3& m, const SymmetricEigen& e, double tolerance) {
  for (int i = 0; i < 3; ++i) {
    const glm::dvec3 residual = m * e.vectors[i] - e.values[i] * e.vectors[i];
    EXPECT_LT(glm::length(residual), tolerance) << "pair " << i;
    EXPECT_NEAR(glm::length(e.vectors[i]), 1.0, 1e-12);
    for (int j = i + 1; j < 3; ++j) EXPECT_NEAR(glm::dot(e.vectors[i], e.vectors[j]), 0.0, 1e-12);
  }
  EXPECT_GE(e.values[0], e.values[1]);
  EXPECT_GE(e.values[1], e.values[2]);
}

TEST(SymmetricEigen, DiagonalMatrixSortedDescending) {
  const glm::dmat3 m = symmetric(1, 0, 0, 3, 0, 2);
  const SymmetricEigen e = symmetric_eigen(m);
  EXPECT_EQ(e.values[0], 3.0);
  EXPECT_EQ(e.values[1], 2.0);
  EXPECT_EQ(e.values[2], 1.0);
  EXPECT_EQ(e.vectors[0], glm::dvec3(0, 1, 0));
  EXPECT_EQ(e.vectors[1], glm::dvec3(0, 0, 1));
  EXPECT_EQ(e.vectors[2], glm::dvec3(1, 0, 0));
}

TEST(SymmetricEigen, RepeatedEigenvalue) {
  // [[2,1,0],[1,2,0],[0,0,3]]: eigenvalues 3 (twice: (1,1,0)/√2 and z) and 1 ((1,-1,0)/√2).
  const glm::dmat3 m = symmetric(2, 1, 0, 2, 0, 3);
  const SymmetricEigen e = symmetric_eigen(m);
  EXPECT_NEAR(e.values[0], 3.0, 1e-14);
  EXPECT_NEAR(e.values[1], 3.0, 1e-14);
  EXPECT_NEAR(e.values[2], 1.0, 1e-14);
  const glm::dvec3 expected = glm::dvec3(1, -1, 0) / std::sqrt(2.0);
  EXPECT_NEAR(glm::length(e.vectors[2] - expected), 0.0, 1e-12);
  expect_eigenpairs(m, e, 1e-12);
}

TEST(SymmetricEigen, RecoversARotatedSpectrum) {
  // R diag(5,2,1) Rᵀ for R a rotation of 30° about z then 45° about x: columns of R are the eigenvectors.
  const double c30 = std::sqrt(3.0) / 2, s30 = 0.5, c45 = std::sqrt(0.5), s45 = std::sqrt(0.5);
  const glm::dmat3 rz(glm::dvec3(c30, s30, 0), glm::dvec3(-s30, c30, 0), glm::dvec3(0, 0, 1));
  const glm::dmat3 rx(glm::dvec3(1, 0, 0), glm::dvec3(0, c45, s45), glm::dvec3(0, -s45, c45));
  const glm::dmat3 r = rx * rz;
  const glm::dmat3 d(glm::dvec3(5, 0, 0), glm::dvec3(0, 2, 0), glm::dvec3(0, 0, 1));
  const glm::dmat3 m = r * d * glm::transpose(r);
  const SymmetricEigen e = symmetric_eigen(m);
  EXPECT_NEAR(e.values[0], 5.0, 1e-13);
  EXPECT_NEAR(e.values[1], 2.0, 1e-13);
  EXPECT_NEAR(e.values[2], 1.0, 1e-13);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(std::abs(glm::dot(e.vectors[i], r[i])), 1.0, 1e-12) << i;
  expect_eigenpairs(m, e, 1e-12);
}

TEST(SymmetricEigen, HandlesZeroAndTinyMatrices) {
  const SymmetricEigen zero = symmetric_eigen(glm::dmat3(0.0));
  EXPECT_EQ(zero.values[0], 0.0);
  EXPECT_EQ(zero.values[2], 0.0);
  const glm::dmat3 tiny = symmetric(2e-20, 1e-20, 0, 2e-20, 0, 3e-20);
  const SymmetricEigen e = symmetric_eigen(tiny);
  EXPECT_NEAR(e.values[2] / 1e-20, 1.0, 1e-12);
  expect_eigenpairs(tiny, e, 1e-32);
}

TEST(SymmetricEigen, CanonicalSignMakesTheLargestComponentPositive) {
  EXPECT_EQ(canonical_sign(glm::dvec3(0.1, -0.9, 0.2)), glm::dvec3(-0.1, 0.9, -0.2));
  EXPECT_EQ(canonical_sign(glm::dvec3(-0.5, 0.5, 0)), glm::dvec3(0.5, -0.5, 0));  // tie: first one
  EXPECT_EQ(canonical_sign(glm::dvec3(0, 0, 1)), glm::dvec3(0, 0, 1));
}

std::vector<Atom> atoms_at(const std::vector<glm::dvec3>& positions, double radius) {
  std::vector<Atom> atoms(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    atoms[i].position = positions[i];
    atoms[i].radius = radius;
  }
  return atoms;
}

TEST(MoleculeProperties, BoxCentroidAndBoundingRadiusByHand) {
  const auto atoms = atoms_at({{0, 0, 0}, {2, 0, 0}, {0, 4, 0}, {0, 0, 6}}, 1.0);
  const MoleculeProperties p = compute_molecule_properties(atoms);
  EXPECT_EQ(p.centres.min, glm::dvec3(0, 0, 0));
  EXPECT_EQ(p.centres.max, glm::dvec3(2, 4, 6));
  EXPECT_EQ(p.spheres.min, glm::dvec3(-1, -1, -1));
  EXPECT_EQ(p.spheres.max, glm::dvec3(3, 5, 7));
  EXPECT_EQ(p.centroid, glm::dvec3(0.5, 1.0, 1.5));
  EXPECT_NEAR(p.bounding_radius, std::sqrt(21.5) + 1.0, 1e-12);  // the atom at z = 6
}

TEST(MoleculeProperties, PrincipalAxisOfALineIsItsDirectionAndTheDefaultUp) {
  std::vector<glm::dvec3> positions;
  for (int t = -2; t <= 2; ++t) positions.push_back(glm::dvec3(-t, -t, 0));
  const MoleculeProperties p = compute_molecule_properties(atoms_at(positions, 1.0));
  const glm::dvec3 diagonal = glm::dvec3(1, 1, 0) / std::sqrt(2.0);
  EXPECT_NEAR(glm::length(p.principal_axes[0] - diagonal), 0.0, 1e-12);  // sign: first largest positive
  EXPECT_NEAR(p.principal_variances[0], 4.0, 1e-12);  // mean of 2t² over t = -2..2
  EXPECT_NEAR(p.principal_variances[1], 0.0, 1e-12);
  EXPECT_EQ(p.up, p.principal_axes[0]);
  const MoleculeProperties given = compute_molecule_properties(atoms_at(positions, 1.0), glm::dvec3(0, 0, -2));
  EXPECT_EQ(given.up, glm::dvec3(0, 0, -1));
}

TEST(MoleculeProperties, StaysAccurateFarFromTheOrigin) {
  std::vector<glm::dvec3> positions;
  for (int t = -2; t <= 2; ++t) positions.push_back(glm::dvec3(1e7 + t, 1e7 + t, -1e7));
  const MoleculeProperties p = compute_molecule_properties(atoms_at(positions, 1.5));
  EXPECT_NEAR(p.principal_variances[0], 4.0, 1e-6);
  EXPECT_NEAR(p.centroid.x, 1e7, 1e-6);
  EXPECT_NEAR(p.bounding_radius, 2.0 * std::sqrt(2.0) + 1.5, 1e-6);
}

TEST(MoleculeProperties, RejectsNoAtomsAndAZeroUpAxis) {
  EXPECT_THROW(compute_molecule_properties({}), std::invalid_argument);
  EXPECT_THROW(compute_molecule_properties(atoms_at({{0, 0, 0}}, 1.0), glm::dvec3(0.0)), std::invalid_argument);
}

}  // namespace
}  // namespace nano::structure
