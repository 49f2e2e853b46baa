#include "bake/structure/selection.hpp"

#include <gtest/gtest.h>

namespace nano::structure {
namespace {

Atom atom(std::string name, int residue, double occupancy = 1.0, char alt = ' ', std::string residue_name = "ALA",
          int model = 0, std::string element = "C") {
  Atom a;
  a.atom_name = std::move(name);
  a.residue_number = residue;
  a.residue_name = std::move(residue_name);
  a.chain = "A";
  a.occupancy = occupancy;
  a.alt_loc = alt;
  a.model_index = model;
  a.element = std::move(element);
  a.position = glm::dvec3(occupancy, residue, model);
  return a;
}

TEST(Selection, KeepsTheFirstModelUnlessAskedForAll) {
  const std::vector<Atom> atoms = {atom("CA", 1, 1, ' ', "ALA", 0), atom("CA", 1, 1, ' ', "ALA", 1)};
  EXPECT_EQ(select_atoms(atoms, {}).atoms.size(), 1u);
  const Selection all = select_atoms(atoms, {.all_models = true});
  EXPECT_EQ(all.atoms.size(), 2u);  // the model is part of the identity
  EXPECT_EQ(all.duplicates_without_alt_loc, 0u);
}

TEST(Selection, RemovesWaterByResidueName) {
  const std::vector<Atom> atoms = {atom("O", 1, 1, ' ', "HOH", 0, "O"), atom("O", 2, 1, ' ', "WAT", 0, "O"),
                                   atom("O", 3, 1, ' ', "DOD", 0, "O"), atom("O", 4, 1, ' ', "H2O", 0, "O"),
                                   atom("O", 5, 1, ' ', "SO4", 0, "O")};
  EXPECT_EQ(select_atoms(atoms, {}).atoms.size(), 1u);
  EXPECT_EQ(select_atoms(atoms, {.keep_water = true}).atoms.size(), 5u);
  EXPECT_TRUE(is_water_residue("HOH"));
  EXPECT_FALSE(is_water_residue("HEM"));
}

TEST(Selection, KeepsHydrogensUnlessAskedNotTo) {
  const std::vector<Atom> atoms = {atom("N", 1, 1, ' ', "ALA", 0, "N"), atom("H", 1, 1, ' ', "ALA", 0, "H")};
  EXPECT_EQ(select_atoms(atoms, {}).atoms.size(), 2u);
  const Selection no_h = select_atoms(atoms, {.keep_hydrogens = false});
  ASSERT_EQ(no_h.atoms.size(), 1u);
  EXPECT_EQ(no_h.atoms[0].element, "N");
}

TEST(Selection, HighestOccupancyWinsAmongAlternateLocationsEvenInSplitResidues) {
  // Residue 1 is split: its B conformer comes after residue 2, as in real files.
  const std::vector<Atom> atoms = {atom("CB", 1, 0.3, 'A'), atom("CA", 2, 1.0), atom("CB", 1, 0.7, 'B'), atom("CG", 1, 0.4, 'A')};
  const Selection s = select_atoms(atoms, {});
  ASSERT_EQ(s.atoms.size(), 3u);
  EXPECT_EQ(s.atoms[0].atom_name, "CB");
  EXPECT_EQ(s.atoms[0].alt_loc, 'B');  // the winner takes the first slot of its identity
  EXPECT_DOUBLE_EQ(s.atoms[0].occupancy, 0.7);
  EXPECT_EQ(s.atoms[1].atom_name, "CA");
  EXPECT_EQ(s.duplicates_without_alt_loc, 0u);
}

TEST(Selection, TiesGoToTheFirstInTheFile) {
  const std::vector<Atom> atoms = {atom("CB", 1, 0.5, 'A'), atom("CB", 1, 0.5, 'B')};
  const Selection s = select_atoms(atoms, {});
  ASSERT_EQ(s.atoms.size(), 1u);
  EXPECT_EQ(s.atoms[0].alt_loc, 'A');
}

TEST(Selection, CountsDuplicatesThatAreNotAlternateLocations) {
  // Same identity without altloc: e.g. residue numbers that wrapped in a big MD file.
  std::vector<Atom> atoms = {atom("C1", 1), atom("C1", 1), atom("C1", 1, 1.0, ' ', "ALA", 0, "C")};
  atoms[2].insertion_code = "A";  // a different identity
  const Selection s = select_atoms(atoms, {});
  EXPECT_EQ(s.atoms.size(), 2u);
  EXPECT_EQ(s.duplicates_without_alt_loc, 1u);
}

TEST(Selection, ChainIsPartOfTheIdentity) {
  std::vector<Atom> atoms = {atom("CA", 1), atom("CA", 1)};
  atoms[1].chain = "B";
  EXPECT_EQ(select_atoms(atoms, {}).atoms.size(), 2u);
}

}  // namespace
}  // namespace nano::structure
