// The .sph sphere tree reader on cellPACK's own HIV protease file (values read off the file) and on
// malformed text, each refused with its line.
#include <gtest/gtest.h>

#include <filesystem>

#include "bake/cellpack/sphere_tree.hpp"
#include "common/error.hpp"

namespace nano::cellpack {
namespace {

std::string sphere_tree_error(const std::string& text) {
  try {
    parse_sphere_tree(text, "t.sph");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SphereTree, HivProteaseOfCellpacksDatabase) {
  const SphereTree t = read_sphere_tree(std::filesystem::path(NANO_SOURCE_DIR) / "tests/cellpack/data/HIV1_PR_7hvp_0_1_0.sph");
  EXPECT_EQ(t.min_radius, 16.0);
  EXPECT_EQ(t.max_radius, 34.5);
  ASSERT_EQ(t.levels.size(), 1u);
  ASSERT_EQ(t.levels[0].size(), 6u);
  EXPECT_EQ(t.levels[0][0], glm::dvec4(-16.01, 2.88, 3.47, 15.61));
  EXPECT_EQ(t.levels[0][5], glm::dvec4(1.20, 7.97, 4.57, 14.75));
}

TEST(SphereTree, LevelsWithChildIndicesAndComments) {
  const SphereTree t = parse_sphere_tree("# c\n1 20\n2\n1\n0 0 0 20 0 1\n\n2\n-5 0 0 10\n5 0 0 10\n", "t.sph");
  ASSERT_EQ(t.levels.size(), 2u);
  EXPECT_EQ(t.levels[0][0], glm::dvec4(0, 0, 0, 20));
  EXPECT_EQ(t.levels[1][1], glm::dvec4(5, 0, 0, 10));
}

TEST(SphereTree, MalformedFilesNameTheLine) {
  EXPECT_NE(sphere_tree_error("").find("t.sph:end: the file ends before \"rmin rmax\""), std::string::npos);
  EXPECT_NE(sphere_tree_error("1 2\n1\n2\n0 0 0 1\n").find("t.sph:end: the file ends before \"x y z r\""), std::string::npos);
  EXPECT_NE(sphere_tree_error("1 2\n1\n1\n0 0 zero 1\n").find("t.sph:line 4: expected \"x y z r\""), std::string::npos);
  EXPECT_NE(sphere_tree_error("1 2\n1\n1\n0 0 0 -1\n").find("line 4: expected a sphere radius > 0"), std::string::npos);
  EXPECT_NE(sphere_tree_error("1 2\n1.5\n").find("line 2: the number of levels must be a whole number"), std::string::npos);
  EXPECT_NE(sphere_tree_error("1 2\n1\n1e9\n").find("line 3: a sphere count must be a whole number in [0, 1000000]"), std::string::npos);
  EXPECT_NE(sphere_tree_error("1 nan\n").find("line 1"), std::string::npos);
  EXPECT_NE(sphere_tree_error("1 2\n1\n1\n0 0 0 1e999\n").find("line 4"), std::string::npos);
  EXPECT_THROW(read_sphere_tree("absent.sph"), InputError);
}

}  // namespace
}  // namespace nano::cellpack
