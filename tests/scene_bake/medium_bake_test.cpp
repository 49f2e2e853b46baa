// The medium as the baker makes it: its region in whole boxes, the periodic recipe, one exclusion
// field per compartment, and its estimated copies against a brute-force count of the copies the
// rule keeps around an analytic sphere; and how PackageContent stores it.
#include "bake/scene_bake/medium_bake.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "bake/mesh/sphere_mesh.hpp"
#include "bake/scene_bake/package_content.hpp"

namespace nano::scene_bake {
namespace {

constexpr double kSphereRadius = 300.0, kShell = 10.0, kClearance = 1.0, kCube = 40.0;

BakedMolecule pair_molecule() {
  BakedMolecule m;
  m.name = "pair";
  m.source = "pair.pdb";
  structure::Atom a;
  a.position = {-1, 0, 0};
  a.radius = 1.5;
  a.element = "C";
  structure::Atom b = a;
  b.position = {1, 0, 0};
  m.atoms = {a, b};
  m.properties.spheres.min = {-2.5, -1.5, -1.5};
  m.properties.spheres.max = {2.5, 1.5, 1.5};
  m.properties.bounding_radius = 2.5;
  return m;
}

struct Fixture {
  std::vector<BakedMolecule> library{pair_molecule()};
  scene::SceneDescription scene;
  BakedWangSet cubes;
  mesh::ProxyMesh sphere = mesh::make_sphere_mesh(2000, kSphereRadius);
  std::vector<scene::PlacedInstance> placed;

  Fixture() {
    scene.molecules.push_back({});
    scene.molecules[0].name = "pair";
    scene::SolubleDescription plasma;
    plasma.name = "plasma";
    plasma.cube_size = kCube;
    plasma.face_colours = 2;
    plasma.cubes = 64;
    plasma.clearance = kClearance;
    plasma.molecules.push_back({{"pair", 0}, {scene::VolumeAbundance::Unit::per_um3, 4e7}});  // ~2.6 a cube
    scene.solubles.push_back(plasma);
    scene.medium = scene::MediumDescription{{"plasma", 0}, std::nullopt, std::nullopt};
    scene.compartments.push_back({});
    scene.compartments[0].name = "cell";
    cubes = bake_soluble_cubes(plasma, library, 11, 2);
    scene::PlacedInstance p;
    p.compartment = {"cell", 0};
    p.transform = scene::identity_transform();
    placed.push_back(p);
  }

  BakedMedium bake(const scene::Box& region) {
    const std::vector<MediumCompartment> walls{{&sphere, std::vector<float>(sphere.triangles.size(), float(kShell))}};
    return bake_medium(scene, region, cubes, library, walls, placed, 5, 2);
  }
};

TEST(MediumBake, TheRegionIsWholeBoxesFromItsMinimum) {
  Fixture f;
  const BakedMedium m = f.bake({glm::dvec3(-600, -600, -590), glm::dvec3(600, 610, 600)});
  EXPECT_EQ(m.boxes, glm::uvec3(30, 31, 30));  // 1200 / 40, ceil(1210 / 40), ceil(1190 / 40)
  EXPECT_EQ(m.region.min, glm::dvec3(-600, -600, -590));
  EXPECT_EQ(m.region.max, glm::dvec3(600, 640, 610));
  EXPECT_EQ(m.box_edge, kCube);
  EXPECT_EQ(m.clearance, kClearance);
  EXPECT_TRUE(m.recipe.periodic);
  EXPECT_EQ(m.recipe.size, (std::array<int, 3>{kMediumRecipeCells, kMediumRecipeCells, kMediumRecipeCells}));
  ASSERT_EQ(m.fields.size(), 1u);
  EXPECT_GT(m.fields[0].values.size(), 1000u);
}

TEST(MediumBake, CopiesPerBoxAverageTheRecipesCubes) {
  Fixture f;
  tiles::TilingRecipe recipe;
  recipe.dims = 3;
  recipe.size = {2, 1, 1};
  recipe.cells = {0, 5};
  const std::vector<double> per_box = medium_copies_per_box(recipe, f.cubes, 1);
  const double expected = 0.5 * double(f.cubes.set.tiles[0].instances.size() + f.cubes.set.tiles[5].instances.size());
  EXPECT_DOUBLE_EQ(per_box[0], expected);
}

// The estimate against every copy of every box counted by hand: a copy is kept when its centre
// stands at least r + clearance from the sphere grown by its shell (the field's margin and the
// facets make the rule keep a little less; the estimate counts by field cells).
TEST(MediumBake, EstimatedCopiesMatchABruteForceCountAroundASphere) {
  Fixture f;
  const scene::Box region{glm::dvec3(-600), glm::dvec3(600)};
  const BakedMedium m = f.bake(region);
  const double reach = kSphereRadius + kShell + 2.5 + kClearance;
  double kept = 0;
  for (std::uint32_t k = 0; k < m.boxes.z; ++k)
    for (std::uint32_t j = 0; j < m.boxes.y; ++j)
      for (std::uint32_t i = 0; i < m.boxes.x; ++i) {
        const std::uint32_t cube = m.recipe.at(int(i % kMediumRecipeCells), int(j % kMediumRecipeCells), int(k % kMediumRecipeCells));
        for (const tiles::Instance& c : f.cubes.set.tiles[cube].instances) {
          const glm::dvec3 centre = region.min + glm::dvec3(i, j, k) * kCube + glm::dvec3(c.position);
          if (std::sqrt(glm::dot(centre, centre)) >= reach) ++kept;
        }
      }
  ASSERT_EQ(m.counts.size(), 1u);
  EXPECT_EQ(m.counts[0].name, "pair");
  EXPECT_NEAR(m.counts[0].copies / kept, 1.0, 0.03) << m.counts[0].copies << " estimated, " << kept << " counted";
  EXPECT_DOUBLE_EQ(m.counts[0].atoms, 2.0 * m.counts[0].copies);
  EXPECT_GT(m.copies_in_region, m.counts[0].copies);
}

TEST(MediumBake, PackageContentStoresTheRecordRecipeAndFields) {
  Fixture f;
  const BakedMedium m = f.bake({glm::dvec3(-600), glm::dvec3(600)});
  PackageContent content;
  content.add_molecule(f.library[0]);
  const TileRange cubes = content.add_wang_set(f.cubes, f.library);
  content.add_medium(m, cubes, 9);
  ASSERT_EQ(content.medium.size(), 1u);
  const gpu::Medium& r = content.medium[0];
  EXPECT_EQ(r.region_min, glm::vec4(-600, -600, -600, float(kCube)));
  EXPECT_EQ(r.region_max, glm::vec4(600, 600, 600, float(kClearance)));
  EXPECT_EQ(glm::uvec3(r.boxes), glm::uvec3(30));
  EXPECT_EQ(r.boxes.w, 0u);  // the first recipe
  EXPECT_EQ(r.tiles, glm::uvec4(cubes.first, cubes.count, 9u, 0u));
  ASSERT_EQ(content.exclusion_fields.size(), 1u);
  const gpu::ExclusionField& field = content.exclusion_fields[0];
  EXPECT_EQ(field.dims.w, 0u);
  EXPECT_EQ(std::size_t(field.dims.x) * field.dims.y * field.dims.z, content.exclusion_values.size());
  EXPECT_FLOAT_EQ(field.origin.w, float(m.fields[0].spacing));
  EXPECT_FLOAT_EQ(field.limits.x, float(m.fields[0].margin));
  EXPECT_EQ(content.exclusion_values, m.fields[0].values);
  EXPECT_EQ(content.recipes.size(), 1u);
  EXPECT_EQ(content.recipes[0].index_count, std::uint32_t(kMediumRecipeCells * kMediumRecipeCells * kMediumRecipeCells));
}

}  // namespace
}  // namespace nano::scene_bake
