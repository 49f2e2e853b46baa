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
using nano::scene_bake::load_baked_molecule;

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
  EXPECT_DOUBLE_EQ(nano::scene_bake::srgb_to_linear(0.0), 0.0);
  EXPECT_DOUBLE_EQ(nano::scene_bake::srgb_to_linear(1.0), 1.0);
  EXPECT_NEAR(nano::scene_bake::srgb_to_linear(0.04045), 0.04045 / 12.92, 1e-15);
  EXPECT_NEAR(nano::scene_bake::srgb_to_linear(0.2), 0.0331047666, 1e-9);
}

TEST(MoleculeLibrary, DefaultColoursAreDistinctAndInRange) {
  for (std::size_t i = 0; i < 12; ++i) {
    const glm::dvec3 a = nano::scene_bake::default_molecule_colour(i);
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(a[c], 0.0);
      EXPECT_LE(a[c], 1.0);
    }
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_GT(glm::length(a - nano::scene_bake::default_molecule_colour(j)), 0.05) << i << " vs " << j;
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
  const auto library = nano::scene_bake::load_molecule_library(scene);
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

namespace {

using nano::scene_bake::load_lipid_patch;

// Two lipids of two atoms each, one per leaflet: centroids (1, 2, 14) and (5, 6, 6), so the
// mid-plane (mean z of all four atoms) is at z = 10.
constexpr const char* kTwoLipidPatch =
    "CRYST1   40.000   50.000   60.000  90.00  90.00  90.00 P 1           1\n"
    "HETATM    1  C1  POP A   1       0.000   2.000  15.000  1.00  0.00           C\n"
    "HETATM    2  C2  POP A   1       2.000   2.000  13.000  1.00  0.00           C\n"
    "HETATM    3  C1  POP A   2       5.000   5.000   6.000  1.00  0.00           C\n"
    "HETATM    4  C2  POP A   2       5.000   7.000   6.000  1.00  0.00           C\n"
    "HETATM    5  O   HOH A   3       9.000   9.000   9.000  1.00  0.00           O\n"
    "END\n";

nano::scene::LipidPatchDescription patch_description(const fs::path& file) {
  nano::scene::LipidPatchDescription d;
  d.name = "POPC";
  d.file = file;
  d.colour = glm::dvec3(1.0, 0.0, 0.0);
  d.clearance = 0.7;
  return d;
}

TEST(LipidPatch, EachResidueIsATypeAtItsCentroidAboveTheMidPlane) {
  std::vector<nano::scene_bake::BakedMolecule> library(3);  // the scene's own molecules come first
  const auto patch = load_lipid_patch(patch_description(write_temp("nano_two_lipids.pdb", kTwoLipidPatch)), 3, library);
  EXPECT_DOUBLE_EQ(patch.period_x, 40.0);
  EXPECT_DOUBLE_EQ(patch.period_y, 50.0);
  EXPECT_DOUBLE_EQ(patch.clearance, 0.7);
  ASSERT_EQ(library.size(), 5u);  // waters are not lipids
  EXPECT_EQ(patch.molecules, (std::vector<std::uint32_t>{3, 4}));
  ASSERT_EQ(patch.positions.size(), 2u);
  EXPECT_EQ(patch.positions[0], glm::dvec3(1, 2, 4));
  EXPECT_EQ(patch.positions[1], glm::dvec3(5, 6, -4));
  const auto& first = library[3];
  EXPECT_EQ(first.name, "POPC");
  EXPECT_EQ(first.source, "nano_two_lipids.pdb");
  ASSERT_EQ(first.atoms.size(), 2u);
  EXPECT_EQ(first.atoms[0].position, glm::dvec3(-1, 0, 1));  // molecule space: the patch's orientation kept
  EXPECT_EQ(first.up, glm::dvec3(0, 0, 1));
  EXPECT_DOUBLE_EQ(first.linear_colour.x, 1.0);
  EXPECT_DOUBLE_EQ(first.linear_colour.y, 0.0);
}

TEST(LipidPatch, BilayerThicknessRunsFromTheLowestToTheHighestAtomSurface) {
  std::vector<nano::scene_bake::BakedMolecule> library;
  const auto patch = load_lipid_patch(patch_description(write_temp("nano_two_lipids_thickness.pdb", kTwoLipidPatch)), 0, library);
  // Atoms at z = 15 and 6 about the mid-plane z = 10: from 6 − r to 15 + r, r the carbon radius.
  const double r = library.at(0).atoms.at(0).radius;
  ASSERT_GT(r, 1.0);
  EXPECT_DOUBLE_EQ(nano::scene_bake::bilayer_thickness(patch, library), 9.0 + 2.0 * r);
}

TEST(LipidPatch, BundledPopcBilayerHas128LipidsInTwoLeaflets) {
  std::vector<nano::scene_bake::BakedMolecule> library;
  const auto patch = load_lipid_patch(
      patch_description(fs::path(NANO_SOURCE_DIR) / "data" / "structures" / "popc_bilayer.pdb.gz"), 0, library);
  // OpenMM's POPC.pdb (data/structures/SOURCES.md): 128 POPC, 64 per leaflet, 52 heavy atoms each.
  EXPECT_NEAR(patch.period_x, 63.701, 1e-9);
  EXPECT_NEAR(patch.period_y, 66.874, 1e-9);
  ASSERT_EQ(library.size(), 128u);
  int upper = 0;
  for (std::size_t i = 0; i < library.size(); ++i) {
    EXPECT_EQ(library[i].atoms.size(), 52u) << i;
    upper += patch.positions[i].z > 0;
    EXPECT_GT(std::abs(patch.positions[i].z), 3.0) << "a lipid centroid in the mid-plane: " << i;
  }
  EXPECT_EQ(upper, 64);
}

TEST(LipidPatch, BoxAndFormatErrorsNameTheFile) {
  std::vector<nano::scene_bake::BakedMolecule> library;
  std::string text = kTwoLipidPatch;
  const auto expect_error = [&](const std::string& file_text, const std::string& name, const std::string& what) {
    const fs::path file = write_temp(name, file_text);
    try {
      load_lipid_patch(patch_description(file), 0, library);
      ADD_FAILURE() << what;
    } catch (const nano::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  expect_error(text.substr(text.find('\n') + 1), "nano_patch_no_box.pdb", "CRYST1");
  std::string skewed = text;
  skewed.replace(skewed.find("90.00 P"), 5, "120.0");
  expect_error(skewed, "nano_patch_skewed.pdb", "orthogonal");
  expect_error("data_x\n_cell.length_a 40\n", "nano_patch.cif", "PDB file");
  EXPECT_TRUE(library.empty());
}

// Three lipids of two kinds: a POPC and a cholesterol (CHL1) above the mid-plane, a POPC below.
constexpr const char* kTwoKindPatch =
    "CRYST1   40.000   50.000   60.000  90.00  90.00  90.00 P 1           1\n"
    "ATOM      1  C1  POPCA   1       0.000   2.000  15.000  1.00  0.00           C\n"
    "ATOM      2  C2  POPCA   1       2.000   2.000  13.000  1.00  0.00           C\n"
    "ATOM      3  C1  CHL1A   2      10.000   2.000  14.000  1.00  0.00           C\n"
    "ATOM      4  O3  CHL1A   2      10.000   4.000  16.000  1.00  0.00           O\n"
    "ATOM      5  C1  POPCB   3       5.000   5.000   2.000  1.00  0.00           C\n"
    "ATOM      6  C2  POPCB   3       5.000   7.000   2.000  1.00  0.00           C\n"
    "END\n";

nano::scene::LipidPatchDescription two_kind_description() {
  nano::scene::LipidPatchDescription d;
  d.file = write_temp("nano_two_kinds.pdb", kTwoKindPatch);
  d.kinds = {{"CHL1", "cholesterol", glm::dvec3(1.0, 1.0, 0.0)}, {"POPC", "POPC", std::nullopt}};
  return d;
}

TEST(LipidPatch, KindsNameAndColourEachLipidByItsResidueName) {
  std::vector<nano::scene_bake::BakedMolecule> library;
  const auto patch = load_lipid_patch(two_kind_description(), 0, library);
  ASSERT_EQ(library.size(), 3u);
  EXPECT_EQ(library[0].name, "POPC");
  EXPECT_EQ(library[1].name, "cholesterol");
  EXPECT_EQ(library[1].linear_colour, glm::dvec3(1.0, 1.0, 0.0));  // sRGB 1 is linear 1
  EXPECT_EQ(library[2].name, "POPC");
  EXPECT_EQ(library[0].linear_colour, library[2].linear_colour);  // one kind, one colour
  EXPECT_NE(library[0].linear_colour, library[1].linear_colour);
  const auto [outer, inner] = nano::scene_bake::patch_leaflet_counts(patch, library);
  EXPECT_EQ(outer, (nano::scene::LeafletCounts{{"POPC", 1}, {"cholesterol", 1}}));
  EXPECT_EQ(inner, (nano::scene::LeafletCounts{{"POPC", 1}}));
}

TEST(LipidPatch, AResidueNoKindNamesIsRefusedNamingItAndTheFile) {
  std::vector<nano::scene_bake::BakedMolecule> library;
  nano::scene::LipidPatchDescription d = two_kind_description();
  d.kinds.pop_back();
  try {
    load_lipid_patch(d, 0, library);
    FAIL() << "expected an InputError";
  } catch (const nano::InputError& e) {
    EXPECT_EQ(e.file(), d.file.string());
    EXPECT_EQ(e.where(), "lipid_patch.kinds");
    EXPECT_EQ(e.rule(), "residue POPC 1 (chain A) is none of the kinds the scene lists (CHL1)");
  }
}

// A stand-in is its spheres as pseudo-atoms, centred like any molecule, and says what it is.
TEST(MoleculeLibrary, AStandInIsItsSpheresAndSaysSo) {
  nano::scene::MoleculeDescription description;
  description.name = "protease";
  description.stand_in_spheres = {{-10, 4, 0, 12}, {10, 4, 0, 8}};
  description.stand_in_from = "HIV1_PR.sph";
  const auto molecule = load_baked_molecule(description, 0);
  ASSERT_EQ(molecule.atoms.size(), 2u);
  EXPECT_DOUBLE_EQ(molecule.atoms[0].radius, 12.0);
  EXPECT_DOUBLE_EQ(molecule.atoms[1].position.x, 10.0);  // centroid (0, 4, 0) taken off
  EXPECT_DOUBLE_EQ(molecule.atoms[1].position.y, 0.0);
  EXPECT_NEAR(molecule.properties.bounding_radius, 22.0, 1e-12);
  EXPECT_EQ(molecule.source, "stand-in (HIV1_PR.sph, 2 spheres)");
  EXPECT_TRUE(nano::scene_bake::is_stand_in_source(molecule.source));
  EXPECT_FALSE(nano::scene_bake::is_stand_in_source("4hhb.pdb"));
}

}  // namespace
