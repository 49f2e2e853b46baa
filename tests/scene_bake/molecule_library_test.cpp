#include "bake/scene_bake/molecule_library.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "common/error.hpp"

namespace {

namespace fs = std::filesystem;
using nano::bake::load_baked_molecule;

// Four carbons at the corners of a 4 x 2 rectangle in z = 3, centred on (12, 21, 3), written in
// PDB's fixed columns; the expected molecule-space values follow by hand.
constexpr const char* kRectanglePdb =
    "ATOM      1  C1  LIG A   1      10.000  20.000   3.000  1.00  0.00           C\n"
    "ATOM      2  C2  LIG A   1      14.000  20.000   3.000  1.00  0.00           C\n"
    "ATOM      3  C3  LIG A   1      14.000  22.000   3.000  1.00  0.00           C\n"
    "ATOM      4  C4  LIG A   1      10.000  22.000   3.000  1.00  0.00           C\n"
    "END\n";

fs::path write_temp(const std::string& name, const std::string& text) {
  const fs::path path = fs::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path;
}

TEST(MoleculeLibrary, RecentresAtomsOnTheCentroidAndKeepsTheShape) {
  nano::scene::MoleculeDescription description;
  description.name = "rectangle";
  description.file = write_temp("nano_molecule_library_rectangle.pdb", kRectanglePdb);
  const auto molecule = load_baked_molecule(description, 0);

  ASSERT_EQ(molecule.atoms.size(), 4u);
  EXPECT_DOUBLE_EQ(molecule.atoms[0].position.x, -2.0);
  EXPECT_DOUBLE_EQ(molecule.atoms[0].position.y, -1.0);
  EXPECT_DOUBLE_EQ(molecule.atoms[0].position.z, 0.0);
  EXPECT_DOUBLE_EQ(molecule.atoms[2].position.x, 2.0);
  EXPECT_DOUBLE_EQ(molecule.atoms[2].position.y, 1.0);
  EXPECT_NEAR(glm::length(molecule.properties.centroid), 0.0, 1e-12);
  // Corner distance sqrt(5) plus the carbon radius 1.7 Å (Mantina).
  EXPECT_NEAR(molecule.properties.bounding_radius, std::sqrt(5.0) + 1.7, 1e-9);
  EXPECT_EQ(molecule.name, "rectangle");
  EXPECT_EQ(molecule.source, "nano_molecule_library_rectangle.pdb");
  // Largest spread is along x, so the principal up axis is ±x.
  EXPECT_NEAR(std::abs(molecule.up.x), 1.0, 1e-9);
}

TEST(MoleculeLibrary, GivenUpAxisAndColourAreUsed) {
  nano::scene::MoleculeDescription description;
  description.name = "rectangle";
  description.file = write_temp("nano_molecule_library_rectangle.pdb", kRectanglePdb);
  description.up_axis = glm::dvec3(0.0, 0.0, 1.0);
  description.colour = glm::dvec3(1.0, 0.5, 0.0);
  const auto molecule = load_baked_molecule(description, 0);
  EXPECT_EQ(molecule.up, glm::dvec3(0.0, 0.0, 1.0));
  EXPECT_DOUBLE_EQ(molecule.linear_colour.x, 1.0);
  EXPECT_NEAR(molecule.linear_colour.y, 0.21404114, 1e-7);  // sRGB 0.5 -> linear
  EXPECT_DOUBLE_EQ(molecule.linear_colour.z, 0.0);
}

TEST(MoleculeLibrary, SrgbToLinearMatchesTheStandardCurve) {
  EXPECT_DOUBLE_EQ(nano::bake::srgb_to_linear(0.0), 0.0);
  EXPECT_DOUBLE_EQ(nano::bake::srgb_to_linear(1.0), 1.0);
  EXPECT_NEAR(nano::bake::srgb_to_linear(0.04045), 0.04045 / 12.92, 1e-15);
  EXPECT_NEAR(nano::bake::srgb_to_linear(0.2), 0.0331047666, 1e-9);
}

TEST(MoleculeLibrary, DefaultColoursAreDistinctAndInRange) {
  for (std::size_t i = 0; i < 12; ++i) {
    const glm::dvec3 a = nano::bake::default_molecule_colour(i);
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(a[c], 0.0);
      EXPECT_LE(a[c], 1.0);
    }
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_GT(glm::length(a - nano::bake::default_molecule_colour(j)), 0.05) << i << " vs " << j;
  }
}

TEST(MoleculeLibrary, LoadsEveryMoleculeOfTheSceneInOrder) {
  nano::scene::SceneDescription scene;
  for (const char* name : {"first", "second"}) {
    nano::scene::MoleculeDescription d;
    d.name = name;
    d.file = write_temp("nano_molecule_library_rectangle.pdb", kRectanglePdb);
    scene.molecules.push_back(d);
  }
  const auto library = nano::bake::load_molecule_library(scene);
  ASSERT_EQ(library.size(), 2u);
  EXPECT_EQ(library[0].name, "first");
  EXPECT_EQ(library[1].name, "second");
}

TEST(MoleculeLibrary, UnreadableStructureNamesTheFile) {
  nano::scene::MoleculeDescription description;
  description.name = "missing";
  description.file = "/nonexistent/nano_missing.pdb";
  try {
    load_baked_molecule(description, 0);
    FAIL() << "expected an InputError";
  } catch (const nano::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nano_missing.pdb"), std::string::npos) << e.what();
  }
}

}  // namespace
