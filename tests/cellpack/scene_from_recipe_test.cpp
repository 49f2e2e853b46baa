// A recipe as a scene: amounts converted as cellPACK counts them (molarity per volume, per Å² on a
// surface, nbMol added over the region's size), structures found, what is missing named at once.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "bake/cellpack/scene_from_recipe.hpp"
#include "common/error.hpp"

namespace nano::cellpack {
namespace {

namespace fs = std::filesystem;

const fs::path kSource(NANO_SOURCE_DIR);

ImportOptions bundled_options() {
  ImportOptions o;
  o.structures = kSource / "data/structures";
  o.lipid_patch = kSource / "data/structures/popc_bilayer.pdb.gz";
  o.scene_folder = kSource / "data";
  return o;
}

TEST(SceneFromRecipe, VesicleInPlasmaAmountsAsCellpackCountsThem) {
  const Recipe r = read_recipe(kSource / "tests/cellpack/data/vesicle_in_plasma.json");
  const ImportResult out = scene_from_recipe(r, bundled_options());
  const Json& s = out.scene;
  EXPECT_EQ(s["molecules"]["albumin"]["file"], "structures/1ao6_a.pdb");
  EXPECT_EQ(s["molecules"]["haemoglobin"]["file"], "structures/4hhb.pdb");  // by id, "4HHB"
  EXPECT_EQ(s["molecules"]["aquaporin"]["up"], Json::array({0.0, 0.0, 1.0}));
  // Outside: the medium over the recipe's box, molarity in mM.
  EXPECT_EQ(s["medium"]["soluble"], "outside");
  EXPECT_EQ(s["medium"]["region"][1], Json::array({4000.0, 4000.0, 4000.0}));
  EXPECT_DOUBLE_EQ(s["solubles"]["outside"]["molecules"][0]["concentration_mM"].get<double>(), 0.6);
  EXPECT_EQ(s["solubles"]["outside"]["cubes"], 64);  // a medium's cube set is complete
  EXPECT_DOUBLE_EQ(s["solubles"]["vesicle"]["molecules"][0]["concentration_mM"].get<double>(), 5.0);
  // Surface: 100 copies over the sphere's 4π·1500² Å².
  const double area_um2 = 4.0 * std::numbers::pi * 1500.0 * 1500.0 * 1e-8;
  EXPECT_NEAR(s["membranes"]["vesicle"]["proteins"][0]["density_per_um2"].get<double>(), 100.0 / area_um2, 1e-9);
  EXPECT_EQ(s["compartments"]["vesicle"]["mesh"]["generate"], "sphere");
  EXPECT_EQ(s["compartments"]["vesicle"]["mesh"]["radius"], 1500.0);
  ASSERT_EQ(out.report.size(), 4u);
  EXPECT_EQ(out.report[0].ingredient, "aquaporin");
  EXPECT_NE(out.report[0].held.find("100 copies on 0.2827 µm²"), std::string::npos) << out.report[0].held;
}

TEST(SceneFromRecipe, SurfaceMolarityIsPerSquareAngstromAndNbMolIsAdded) {
  Recipe r;
  r.file = "r.json";
  Compartment c;
  c.id = "envelope";
  c.geometry = Compartment::Geometry::sphere;
  c.radius = 725;
  Ingredient env;
  env.id = "env";
  env.structure = "1ao6_a.pdb";
  env.molarity = 0.0031;  // cellPACK's HIV-1 Env: ≈ 12 spikes on this envelope
  env.principal_vector = glm::dvec3(0, 0, -1);
  env.offset = glm::dvec3(0, 0, -73);  // the Mesoscope convention: 73 Å outside
  Ingredient inside = env;
  inside.id = "inside";
  inside.molarity = 0.001;
  inside.count = 1000;
  c.surface.push_back(env);
  c.interior.push_back(inside);
  r.compartments.push_back(c);
  const ImportResult out = scene_from_recipe(r, bundled_options());
  const double per_um2 = out.scene["membranes"]["envelope"]["proteins"][0]["density_per_um2"].get<double>();
  const double area_um2 = 4.0 * std::numbers::pi * 725.0 * 725.0 * 1e-8;
  EXPECT_NEAR(per_um2 * area_um2, 0.0031 * 6.02214076e-4 * 4.0 * std::numbers::pi * 725.0 * 725.0, 1e-9);
  EXPECT_NEAR(per_um2 * area_um2, 12.3, 0.1);
  EXPECT_DOUBLE_EQ(out.scene["membranes"]["envelope"]["proteins"][0]["depth"].get<double>(), 73.0);
  const double volume_l = 4.0 / 3.0 * std::numbers::pi * std::pow(725.0, 3) * 1e-27;
  EXPECT_NEAR(out.scene["solubles"]["envelope"]["molecules"][0]["concentration_mM"].get<double>(),
              1.0 + 1000.0 / (6.02214076e23 * volume_l) * 1000.0, 1e-9);
}

TEST(SceneFromRecipe, MissingStructuresAreNamedAtOnceAndRefusalsSayWhy) {
  const Recipe r = read_recipe(kSource / "tests/cellpack/data/nested_spheres.json");
  try {
    ImportOptions o = bundled_options();
    scene_from_recipe(r, o);
    FAIL() << "nested compartments were accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'inner_sphere' lies inside 'outer_sphere'"), std::string::npos) << e.what();
  }
  Recipe flat = r;
  flat.compartments.pop_back();
  try {
    scene_from_recipe(flat, bundled_options());
    FAIL() << "missing structures were accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("2 ingredient structure(s) not found"), std::string::npos) << m;  // green_sphere is one molecule in two regions
    EXPECT_NE(m.find("green_sphere (no structure named; by its id; tried green_sphere, green_sphere.pdb"), std::string::npos) << m;
    EXPECT_NE(m.find("red_sphere"), std::string::npos) << m;
  }
  ImportOptions no_bilayer = bundled_options();
  no_bilayer.lipid_patch.clear();
  Recipe surface_only;
  surface_only.file = "s.json";
  Compartment c;
  c.id = "ball";
  c.geometry = Compartment::Geometry::sphere;
  c.radius = 500;
  c.surface.push_back(Ingredient{.id = "p", .structure = "4hhb"});
  surface_only.compartments.push_back(c);
  EXPECT_THROW(scene_from_recipe(surface_only, no_bilayer), InputError);
}

}  // namespace
}  // namespace nano::cellpack
