// The scene's medium: its key in scene.json, the region it fills, and the refusals of a region that
// cannot hold one of its molecules or surrounds no instance. Expectations are hand-computed.
#include <gtest/gtest.h>

#include "bake/scene/medium_region.hpp"
#include "bake/scene/scene_parser.hpp"
#include "tests/scene/input_error_matchers.hpp"

namespace nano::scene {
namespace {

Json scene_with_medium(const char* medium) {
  std::string text = R"({
    "format": "nanouniverse-scene", "version": 1,
    "molecules": {"albumin": {"file": "a.pdb"}, "hb": {"file": "h.pdb"}},
    "solubles": {"plasma": {"cube_size": 250, "cubes": 64, "clearance": 5,
                            "molecules": [{"molecule": "albumin", "concentration_mM": 0.6}]},
                 "cytoplasm": {"cube_size": 100, "molecules": [{"molecule": "hb", "concentration_mM": 5}]}},
    "compartments": {"cell": {"mesh": {"generate": "sphere", "triangles": 1000, "radius": 500}, "soluble": "cytoplasm"}},
    "instances": [{"compartment": "cell"}, {"compartment": "cell", "transform": {"translate": [4000, 0, 0]}}])";
  if (medium) text += std::string(R"(, "medium": )") + medium;
  return parse_json_text(text + "}", "scene.json");
}

SceneDescription parse(const char* medium) { return parse_scene_description(scene_with_medium(medium), "scene.json"); }

// Two cells of radius 600 Å (mesh and shell) at the origin and 4000 Å along x.
std::vector<InstanceSphere> two_cells() { return {{{0, 0, 0}, 600}, {{4000, 0, 0}, 600}}; }

std::vector<MoleculeMeasure> measures(double albumin_radius) {
  std::vector<MoleculeMeasure> m(2);
  m[0].bounding_radius = albumin_radius;
  m[1].bounding_radius = 30;
  return m;
}

TEST(MediumScene, ASceneWithoutAMediumHasNone) { EXPECT_FALSE(parse(nullptr).medium); }

TEST(MediumScene, TheMediumNamesItsSolubleAndItsRegionOrMargin) {
  const SceneDescription s = parse(R"({"soluble": "plasma", "region": [[-1000, -1000, -1000], [5000, 1000, 1000]]})");
  ASSERT_TRUE(s.medium);
  EXPECT_EQ(s.medium->soluble.name, "plasma");
  EXPECT_EQ(s.medium->soluble.index, 0u);
  ASSERT_TRUE(s.medium->region);
  EXPECT_EQ(s.medium->region->max, glm::dvec3(5000, 1000, 1000));
  EXPECT_FALSE(s.medium->margin);
  EXPECT_EQ(*parse(R"({"soluble": "plasma", "margin": 300})").medium->margin, 300.0);
}

TEST(MediumScene, BadMediaAreRefusedAtTheirKey) {
  EXPECT_INPUT_ERROR(parse(R"({"soluble": "plasm"})"), "medium.soluble", "unknown soluble \"plasm\"");
  EXPECT_INPUT_ERROR(parse(R"({"soluble": "plasma", "margin": 1, "region": [[0, 0, 0], [1, 1, 1]]})"), "medium",
                     "not both");
  EXPECT_INPUT_ERROR(parse(R"({"soluble": "plasma", "region": [[0, 0, 0], [0, 1, 1]]})"), "medium.region",
                     "min < max");
  EXPECT_INPUT_ERROR(parse(R"({"soluble": "plasma", "margin": -1})"), "medium.margin", ">= 0");
  EXPECT_INPUT_ERROR(parse(R"({"soluble": "plasma", "fill": true})"), "medium.fill", "unknown key");
  EXPECT_INPUT_ERROR(parse(R"({"region": [[0, 0, 0], [1, 1, 1]]})"), "medium.soluble", "missing required key");
}

TEST(MediumRegion, ByDefaultTheInstancesBoundsGrowByTwoCubes) {
  const SceneDescription s = parse(R"({"soluble": "plasma"})");
  const Box r = medium_region(s, two_cells());
  EXPECT_EQ(r.min, glm::dvec3(-600 - 500, -600 - 500, -600 - 500));
  EXPECT_EQ(r.max, glm::dvec3(4600 + 500, 600 + 500, 600 + 500));
  const Box m = medium_region(parse(R"({"soluble": "plasma", "margin": 0})"), two_cells());
  EXPECT_EQ(m.min, glm::dvec3(-600, -600, -600));
}

TEST(MediumRegion, AGivenRegionIsKeptAsGiven) {
  const Box r = medium_region(parse(R"({"soluble": "plasma", "region": [[1, 2, 3], [4, 5, 6]]})"), two_cells());
  EXPECT_EQ(r.min, glm::dvec3(1, 2, 3));
  EXPECT_EQ(r.max, glm::dvec3(4, 5, 6));
}

TEST(MediumRegion, InstanceSpheresGrowWithTheTransformsStretch) {
  PlacedInstance p;
  p.compartment = {"cell", 0};
  p.transform = {glm::dvec4(2, 0, 0, 10), glm::dvec4(0, 1, 0, 20), glm::dvec4(0, 0, 1, 30)};
  const std::vector<double> radii{100};
  const std::vector<InstanceSphere> s = instance_spheres(std::span<const PlacedInstance>(&p, 1), radii);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].centre, glm::dvec3(10, 20, 30));
  EXPECT_NEAR(s[0].radius, 200, 1e-9);
}

TEST(MediumRegion, ARegionNarrowerThanAMoleculeIsRefusedWithTheWidthThatWorks) {
  // 80 Å albumin + 2 × 5 Å clearance = 170 Å; the region is 150 Å thick along z.
  const SceneDescription s = parse(R"({"soluble": "plasma", "region": [[-1000, -1000, 0], [5000, 1000, 150]]})");
  EXPECT_INPUT_ERROR(check_medium_region(s, measures(80), two_cells()), "medium.region",
                     "150 Å across on its narrowest axis, less than one copy of 'albumin' (160 Å across, plus 10 Å of clearance)");
  EXPECT_INPUT_ERROR(check_medium_region(s, measures(80), two_cells()), "medium.region", "at least 170 Å");
  EXPECT_NO_THROW(check_medium_region(s, measures(70), two_cells()));
}

TEST(MediumRegion, ARegionThatNoInstanceReachesIsRefusedWithTheirBounds) {
  const SceneDescription s = parse(R"({"soluble": "plasma", "region": [[10000, 0, 0], [20000, 5000, 5000]]})");
  // The nearest sphere (at x = 4000, radius 600) is 5400 Å from the region.
  EXPECT_INPUT_ERROR(check_medium_region(s, measures(40), two_cells()), "medium.region",
                     "meets no compartment instance (the nearest is 5400 Å away; the instances lie within "
                     "[[-600, -600, -600], [4600, 600, 600]])");
  const SceneDescription touching = parse(R"({"soluble": "plasma", "region": [[4500, 0, 0], [20000, 5000, 5000]]})");
  EXPECT_NO_THROW(check_medium_region(touching, measures(40), two_cells()));
}

TEST(MediumRegion, AMediumNeedsTheCompleteCubeSet) {
  Json doc = scene_with_medium(R"({"soluble": "plasma"})");
  doc["solubles"]["plasma"]["cubes"] = 16;
  const SceneDescription s = parse_scene_description(doc, "scene.json");
  EXPECT_INPUT_ERROR(check_medium_region(s, measures(40), two_cells()), "solubles.plasma.cubes",
                     "16 cubes: the medium repeats one recipe through its region, which needs the complete cube set of "
                     "its 2 face colours (\"cubes\": 64)");
}

TEST(MediumRegion, ADerivedRegionIsBlamedOnItsMargin) {
  // One 600 Å cell and margin 0: 1200 Å across, narrower than a 700 Å-radius molecule.
  const SceneDescription s = parse(R"({"soluble": "plasma", "margin": 0})");
  const std::vector<InstanceSphere> one{{{0, 0, 0}, 600}};
  EXPECT_INPUT_ERROR(check_medium_region(s, measures(700), one), "medium.margin", "less than one copy of 'albumin'");
  EXPECT_NO_THROW(check_medium_region(parse(nullptr), measures(700), one));
}

}  // namespace
}  // namespace nano::scene
