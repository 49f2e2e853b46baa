// The level of detail's beads: analytic cases (a residue, a long residue cut into cells, residues
// told apart by chain), the laws every bead set obeys (each atom sphere inside a bead, every atom
// counted once), and real structures read from data/structures.
#include "bake/structure/coarse_beads.hpp"

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "bake/structure/structure_reader.hpp"

namespace nano::structure {
namespace {

Atom atom(glm::dvec3 position, double radius, const std::string& chain, int residue) {
  Atom a;
  a.position = position;
  a.radius = radius;
  a.chain = chain;
  a.residue_name = "ALA";
  a.residue_number = residue;
  return a;
}

// Every atom sphere inside at least one bead, the counts add up to the atoms, and every bead
// reports an atom it holds.
void expect_covering(const std::vector<Atom>& atoms, const std::vector<CoarseBead>& beads) {
  std::size_t counted = 0;
  for (const CoarseBead& b : beads) {
    counted += b.atom_count;
    ASSERT_LT(b.representative, atoms.size());
    const Atom& r = atoms[b.representative];
    EXPECT_LE(glm::length(r.position - b.centre) + r.radius, b.radius + 1e-9);
  }
  EXPECT_EQ(counted, atoms.size());
  for (std::size_t a = 0; a < atoms.size(); ++a) {
    bool held = false;
    for (const CoarseBead& b : beads)
      held = held || glm::length(atoms[a].position - b.centre) + atoms[a].radius <= b.radius + 1e-9;
    EXPECT_TRUE(held) << "atom " << a << " lies outside every bead";
  }
}

TEST(CoarseBeads, SmallResidueIsOneBeadAboutItsCentroid) {
  const std::vector<Atom> atoms = {atom({0, 0, 0}, 1.5, "A", 1), atom({2, 0, 0}, 1.5, "A", 1),
                                   atom({0, 2, 0}, 1.0, "A", 1), atom({0.6, 0.7, 0}, 1.2, "A", 1)};
  const std::vector<CoarseBead> beads = coarse_beads(atoms);
  ASSERT_EQ(beads.size(), 1u);
  const glm::dvec3 centroid(2.6 / 4, 2.7 / 4, 0);
  EXPECT_NEAR(glm::length(beads[0].centre - centroid), 0, 1e-12);
  // Farthest sphere: atom 1 at |(2, 0) − centroid| + 1.5.
  EXPECT_NEAR(beads[0].radius, glm::length(glm::dvec3(2, 0, 0) - centroid) + 1.5, 1e-12);
  EXPECT_EQ(beads[0].representative, 3u);  // (0.6, 0.7) is nearest the centroid
  EXPECT_EQ(beads[0].atom_count, 4u);
  expect_covering(atoms, beads);
}

TEST(CoarseBeads, ResiduesAreToldApartByChainNumberAndInsertionCode) {
  std::vector<Atom> atoms = {atom({0, 0, 0}, 1, "A", 1), atom({1, 0, 0}, 1, "B", 1), atom({0, 1, 0}, 1, "A", 2),
                             atom({0, 0, 1}, 1, "A", 2), atom({1, 1, 0}, 1, "A", 1)};
  atoms[3].insertion_code = "A";
  const std::vector<CoarseBead> beads = coarse_beads(atoms);
  ASSERT_EQ(beads.size(), 4u);
  // Residues in order of their first atom: A1 (atoms 0 and 4), B1, A2, A2A.
  EXPECT_EQ(beads[0].atom_count, 2u);
  EXPECT_NEAR(glm::length(beads[0].centre - glm::dvec3(0.5, 0.5, 0)), 0, 1e-12);
  for (int b = 1; b < 4; ++b) EXPECT_EQ(beads[b].atom_count, 1u);
  EXPECT_EQ(beads[3].representative, 3u);
  expect_covering(atoms, beads);
}

// A 30 Å chain of atoms in one residue (a lipid tail) does not fit one bead: it is cut at the
// 8 Å cells its atom centres fall in, x in [0.1, 29.9] → cells 0 to 3.
TEST(CoarseBeads, LongResidueIsCutIntoCells) {
  std::vector<Atom> atoms;
  for (int k = 0; k < 20; ++k) atoms.push_back(atom({0.1 + 29.8 * k / 19.0, 1, 1}, 1.7, "L", 306));
  const std::vector<CoarseBead> beads = coarse_beads(atoms);
  ASSERT_EQ(beads.size(), 4u);
  for (std::size_t b = 0; b < beads.size(); ++b) {
    EXPECT_GE(beads[b].centre.x, 8.0 * b);
    EXPECT_LT(beads[b].centre.x, 8.0 * (b + 1));
    EXPECT_LE(beads[b].radius, 4.0 + 1.7 + 1e-9) << "a cell's atoms span at most its edge along the chain";
  }
  expect_covering(atoms, beads);
}

TEST(CoarseBeads, SameAtomsSameBeads) {
  std::vector<Atom> atoms;
  for (int k = 0; k < 200; ++k)
    atoms.push_back(atom({std::sin(k * 1.3) * 20, std::cos(k * 0.7) * 20, k * 0.1}, 1.5, k % 3 ? "A" : "B", k / 7));
  const std::vector<CoarseBead> a = coarse_beads(atoms), b = coarse_beads(atoms);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].centre, b[i].centre);
    EXPECT_EQ(a[i].radius, b[i].radius);
    EXPECT_EQ(a[i].representative, b[i].representative);
  }
  expect_covering(atoms, a);
}

TEST(CoarseBeads, RefusesNonFiniteAtomsAndGivesNoBeadsForNoAtoms) {
  EXPECT_TRUE(coarse_beads({}).empty());
  std::vector<Atom> atoms = {atom({0, 0, 0}, 1, "A", 1), atom({std::numeric_limits<double>::quiet_NaN(), 0, 0}, 1, "A", 1)};
  EXPECT_THROW(coarse_beads(atoms), std::invalid_argument);
  atoms[1].position.x = 1;
  atoms[1].radius = 0;
  EXPECT_THROW(coarse_beads(atoms), std::invalid_argument);
}

// Real structures through the reader: haemoglobin's amino-acid residues are beads of their own
// (a few long side chains cut), the spike's too; a lipid (one residue of 46 atoms) is cut into
// fragments. Every atom stays covered.
TEST(CoarseBeads, RealStructures) {
  for (const char* name : {"4hhb.pdb", "6vxx.pdb.gz", "lipid_306.pdb"}) {
    SCOPED_TRACE(name);
    const Molecule m = read_molecule(std::string(NANO_DATA_DIR) + "/structures/" + name, SelectionOptions{});
    const std::vector<CoarseBead> beads = coarse_beads(m.atoms);
    expect_covering(m.atoms, beads);
    std::set<std::tuple<std::string, int, std::string, std::string>> residues;
    for (const Atom& a : m.atoms) residues.insert({a.chain, a.residue_number, a.insertion_code, a.residue_name});
    EXPECT_GE(beads.size(), residues.size());
    if (std::string(name) == "lipid_306.pdb") {
      EXPECT_EQ(residues.size(), 1u);
      EXPECT_GE(beads.size(), 3u) << "a 46-atom lipid spans several 8 Å cells";
    } else {
      EXPECT_LE(beads.size(), residues.size() * 11 / 10) << "at most one residue in ten cut";
      for (const CoarseBead& b : beads) EXPECT_LE(b.radius, 11.0);
    }
  }
}

}  // namespace
}  // namespace nano::structure
