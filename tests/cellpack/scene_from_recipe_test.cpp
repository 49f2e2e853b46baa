// A recipe as a scene: amounts converted as cellPACK counts them (molarity per volume, per Å² on a
// surface, nbMol added over the region's size), structures found, what is missing named at once.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include <glm/geometric.hpp>

#include "bake/cellpack/scene_from_recipe.hpp"
#include "bake/structure/structure_reader.hpp"
#include "common/error.hpp"

namespace nano::cellpack {
namespace {

namespace fs = std::filesystem;

const fs::path kSource(NANO_SOURCE_DIR);
constexpr double kAvogadro = 6.02214076e23;

// How far a bundled structure reaches from its centroid (atom centres plus radii), from the
// structure reader (checked against gemmi in tests/structure).
double reach(const char* file) {
  const std::vector<structure::Atom> atoms = structure::read_molecule(kSource / "data/structures" / file, {}).atoms;
  glm::dvec3 centroid(0.0);
  for (const structure::Atom& a : atoms) centroid += a.position / static_cast<double>(atoms.size());
  double r = 0;
  for (const structure::Atom& a : atoms) r = std::max(r, glm::length(a.position - centroid) + a.radius);
  return r;
}

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
  // The recipe's copies are those of the whole region; the scene packs them into what its membranes
  // leave clear: 50 Å of membrane reach, 5 Å of clearance and the molecule's radius (its structure's
  // reach, not the recipe's encapsulating radius) from the surface.
  const double area = 4.0 * std::numbers::pi * 1500.0 * 1500.0, sphere = 4.0 / 3.0 * std::numbers::pi * std::pow(1500.0, 3);
  const double outside = 8000.0 * 8000.0 * 8000.0 - sphere;
  const double albumin_copies = 0.0006 * kAvogadro * outside * 1e-27;
  EXPECT_NEAR(s["solubles"]["outside"]["molecules"][0]["concentration_mM"].get<double>(),
              albumin_copies / (kAvogadro * (outside - area * (50 + 5 + reach("1ao6_a.pdb"))) * 1e-27) * 1000.0, 1e-12);
  EXPECT_EQ(s["solubles"]["outside"]["cubes"], 64);  // a medium's cube set is complete
  const double haemoglobin_copies = 0.005 * kAvogadro * sphere * 1e-27;
  // Inside the sphere, exactly: the ball of radius 1500 less that depth.
  const double inside = 4.0 / 3.0 * std::numbers::pi * std::pow(1500.0 - (50 + 5 + reach("4hhb.pdb")), 3);
  EXPECT_NEAR(s["solubles"]["vesicle"]["molecules"][0]["concentration_mM"].get<double>(),
              haemoglobin_copies / (kAvogadro * inside * 1e-27) * 1000.0, 1e-12);
  // What the bake is checked against: the copies of the whole region, per µm³ of it.
  ASSERT_EQ(out.report.size(), 4u);
  EXPECT_EQ(out.report[1].molecule, "haemoglobin");
  EXPECT_EQ(out.report[1].scene_region, "vesicle");
  EXPECT_NEAR(out.report[1].expected_copies, haemoglobin_copies, 1e-6);
  EXPECT_NEAR(out.report[1].measure, sphere * 1e-12, 1e-15);
  EXPECT_EQ(out.report[2].scene_region, "medium");
  EXPECT_NEAR(out.report[2].expected_copies, albumin_copies, 1e-6);
  // Surface: 100 copies over the sphere's 4π·1500² Å², kept exactly from tiles packed 1.3 × denser.
  const double area_um2 = area * 1e-8;
  EXPECT_NEAR(s["membranes"]["vesicle"]["proteins"][0]["density_per_um2"].get<double>(), 1.3 * 100.0 / area_um2, 1e-9);
  EXPECT_EQ(s["membranes"]["vesicle"]["proteins"][0]["per_compartment"], 100);
  EXPECT_EQ(s["compartments"]["vesicle"]["mesh"]["generate"], "sphere");
  EXPECT_EQ(s["compartments"]["vesicle"]["mesh"]["radius"], 1500.0);
  EXPECT_EQ(out.report[0].ingredient, "aquaporin");
  EXPECT_TRUE(out.report[0].surface);
  EXPECT_NEAR(out.report[0].expected_copies, 100.0, 1e-9);
  EXPECT_NE(out.report[0].held.find("100 copies kept on 0.2827 µm²"), std::string::npos) << out.report[0].held;
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
  const Json& protein = out.scene["membranes"]["envelope"]["proteins"][0];
  const double area_um2 = 4.0 * std::numbers::pi * 725.0 * 725.0 * 1e-8;
  const double env_copies = 0.0031 * 6.02214076e-4 * 4.0 * std::numbers::pi * 725.0 * 725.0;
  EXPECT_NEAR(out.report[0].expected_copies, env_copies, 1e-9);
  EXPECT_NEAR(env_copies, 12.3, 0.1);
  EXPECT_EQ(protein["per_compartment"], 12);
  EXPECT_NEAR(protein["density_per_um2"].get<double>() * area_um2, 1.3 * env_copies, 1e-9);
  EXPECT_DOUBLE_EQ(out.scene["membranes"]["envelope"]["proteins"][0]["depth"].get<double>(), 73.0);
  // Inside: molarity's copies plus nbMol, in the volume the membrane leaves.
  const double volume = 4.0 / 3.0 * std::numbers::pi * std::pow(725.0, 3);
  const double free = 4.0 / 3.0 * std::numbers::pi * std::pow(725.0 - (50 + 5 + reach("1ao6_a.pdb")), 3);
  const double copies = 0.001 * kAvogadro * volume * 1e-27 + 1000.0;
  EXPECT_NEAR(out.report[1].expected_copies, copies, 1e-9);
  EXPECT_NEAR(out.scene["solubles"]["envelope"]["molecules"][0]["concentration_mM"].get<double>(),
              copies / (kAvogadro * free * 1e-27) * 1000.0, 1e-9);
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

// A recipe whose ball holds `ingredients` inside, its structures looked for where there are none.
Recipe ball_holding(std::vector<Ingredient> ingredients) {
  Recipe r;
  r.file = (kSource / "tests/cellpack/data/ball.json").string();
  Compartment c;
  c.id = "ball";
  c.geometry = Compartment::Geometry::sphere;
  c.radius = 600;
  c.interior = std::move(ingredients);
  r.compartments.push_back(c);
  return r;
}

TEST(SceneFromRecipe, StandInsComeFromTheSphereTreeTheInlineSpheresOrTheEncapsulatingRadius) {
  Ingredient from_tree{.id = "protease", .structure = "7hvp", .molarity = 0.001};
  from_tree.file = (kSource / "tests/cellpack/data/ball.json").string();
  from_tree.sphere_file = "HIV1_PR_7hvp_0_1_0.sph";  // beside the file that names it
  Ingredient inline_spheres{.id = "pair", .molarity = 0.001};
  inline_spheres.spheres = {{-10, 0, 0, 12}, {10, 0, 0, 8}};
  Ingredient radius_only{.id = "ball_protein", .molarity = 0.001, .encapsulating_radius = 40};
  ImportOptions o = bundled_options();
  o.structures = kSource / "tests/cellpack";  // holds no structure
  o.stand_ins = true;
  const ImportResult out = scene_from_recipe(ball_holding({from_tree, inline_spheres, radius_only}), o);
  const Json& m = out.scene["molecules"];
  EXPECT_FALSE(m["protease"].contains("file"));
  // The .sph file's six spheres, read here from its text.
  ASSERT_EQ(m["protease"]["stand_in"]["spheres"].size(), 6u);
  EXPECT_EQ(m["protease"]["stand_in"]["spheres"][0], Json::array({-16.01, 2.88, 3.47, 15.61}));
  EXPECT_EQ(m["protease"]["stand_in"]["from"], "HIV1_PR_7hvp_0_1_0.sph");
  EXPECT_EQ(m["pair"]["stand_in"]["spheres"][1], Json::array({10.0, 0.0, 0.0, 8.0}));
  EXPECT_EQ(m["ball_protein"]["stand_in"]["spheres"], Json::array({Json::array({0.0, 0.0, 0.0, 40.0})}));
  EXPECT_EQ(out.report[0].stand_in, "HIV1_PR_7hvp_0_1_0.sph, 6 spheres");
  EXPECT_EQ(out.report[2].stand_in, "its encapsulating radius, 1 sphere");
  EXPECT_NE(report_text(ball_holding({}), out).find("STAND-IN (structure missing): drawn as the recipe's packing spheres, 2 spheres"),
            std::string::npos);
  // Nothing to draw a stand-in from: still named as missing, saying so.
  Ingredient shapeless{.id = "shapeless", .molarity = 0.001};
  try {
    scene_from_recipe(ball_holding({shapeless}), o);
    FAIL() << "an ingredient with neither structure nor shape was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("shapeless (no structure named; by its id; tried shapeless"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no packing spheres or encapsulating radius to stand in either"), std::string::npos);
  }
  // Without --stand-ins the same recipe is refused, pointing at the option.
  o.stand_ins = false;
  try {
    scene_from_recipe(ball_holding({radius_only}), o);
    FAIL() << "a missing structure was accepted without --stand-ins";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--stand-ins"), std::string::npos) << e.what();
  }
}

// v1 recipes nest by geometry alone (HIV-1's capsid in its envelope): refused by name, as v2's
// explicit nesting is; compartments apart are fine.
TEST(SceneFromRecipe, CompartmentsNestedOrOverlappingByGeometryAreRefused) {
  Recipe r = ball_holding({Ingredient{.id = "hb", .structure = "4hhb", .molarity = 0.001}});
  Compartment capsid = r.compartments[0];
  capsid.id = "capsid";
  capsid.radius = 300;
  capsid.centre = {100, 0, 0};
  r.compartments.push_back(capsid);
  try {
    scene_from_recipe(r, bundled_options());
    FAIL() << "a ball inside a ball was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'capsid' and 'ball' are nested"), std::string::npos) << e.what();
  }
  r.compartments[1].centre = {800, 0, 0};
  EXPECT_THROW(scene_from_recipe(r, bundled_options()), InputError);  // overlapping
  r.compartments[1].centre = {1000, 0, 0};
  EXPECT_EQ(scene_from_recipe(r, bundled_options()).scene["instances"].size(), 2u);  // apart
  // A compartment in other units than Å (a modeller's 1, nm) is named as such, not baked empty.
  r.compartments[1].radius = 0.8;
  try {
    scene_from_recipe(r, bundled_options());
    FAIL() << "a 1.6 Å compartment was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'capsid' is 1.6 Å across, too small to hold a protein"), std::string::npos) << e.what();
  }
}

// A switched-off ingredient (molarity 0, nbMol 0) is left out, said so; both amounts are summed, said so.
TEST(SceneFromRecipe, NothingAskedIsLeftOutAndBothAmountsAreSummedAloud) {
  Ingredient off{.id = "off", .structure = "no_such_file"};
  Ingredient fibre{.id = "snake", .molarity = 1e-6, .encapsulating_radius = 75};
  fibre.type = "Grow";
  Ingredient both{.id = "hb", .structure = "4hhb", .molarity = 0.001, .count = 500};
  const Recipe r = ball_holding({off, both, fibre});
  const ImportResult out = scene_from_recipe(r, bundled_options());
  EXPECT_FALSE(out.scene["molecules"].contains("off"));
  EXPECT_FALSE(out.scene["molecules"].contains("snake"));
  EXPECT_EQ(out.report[2].held, "nothing: a fibre is not placed");
  ASSERT_EQ(out.scene["solubles"]["ball"]["molecules"].size(), 1u);
  EXPECT_EQ(out.report[0].held, "nothing: left out");
  EXPECT_EQ(out.report[1].asked, "molarity 0.001 M + nbMol 500 (both given: their sum, as cellPACK places it)");
  EXPECT_NE(report_text(r, out).find("note: ingredients below give both a molarity and an nbMol"), std::string::npos);
  const double volume = 4.0 / 3.0 * std::numbers::pi * std::pow(600.0, 3);
  EXPECT_NEAR(out.report[1].expected_copies, 0.001 * kAvogadro * volume * 1e-27 + 500, 1e-9);
  // Only switched-off ingredients: the ball has no soluble; with no bilayer either it holds nothing.
  ImportOptions no_bilayer = bundled_options();
  no_bilayer.lipid_patch.clear();
  EXPECT_THROW(scene_from_recipe(ball_holding({off}), no_bilayer), InputError);
  EXPECT_FALSE(scene_from_recipe(ball_holding({off}), bundled_options()).scene["compartments"]["ball"].contains("soluble"));
}

// A recipe of its cytoplasm alone (BloodPlasma) fills its bounding box: a box compartment holding
// the recipe's copies of the box's volume, packed into what its faces leave (clearance and radius).
TEST(SceneFromRecipe, ACytoplasmAloneFillsTheRecipesBox) {
  Recipe r;
  r.file = "plasma.json";
  r.box_min = glm::dvec3(-350, -600, -1100);
  r.box_max = glm::dvec3(350, 600, 900);
  r.outside.push_back(Ingredient{.id = "albumin", .structure = "1ao6_a.pdb", .molarity = 0.0006, .encapsulating_radius = 45});
  const ImportResult out = scene_from_recipe(r, bundled_options());
  const Json& s = out.scene;
  EXPECT_FALSE(s.contains("medium"));
  EXPECT_EQ(s["compartments"]["cytoplasm"]["mesh"], (Json{{"generate", "box"}, {"size", {700.0, 1200.0, 2000.0}}}));
  EXPECT_EQ(s["instances"][0]["transform"]["translate"], Json::array({0.0, 0.0, -100.0}));
  const double volume = 700.0 * 1200.0 * 2000.0, d = 2.0 * (5 + reach("1ao6_a.pdb"));
  const double copies = 0.0006 * kAvogadro * volume * 1e-27;
  EXPECT_NEAR(out.report[0].expected_copies, copies, 1e-9);
  EXPECT_EQ(out.report[0].scene_region, "cytoplasm");
  EXPECT_NEAR(s["solubles"]["cytoplasm"]["molecules"][0]["concentration_mM"].get<double>(),
              copies / (kAvogadro * (700.0 - d) * (1200.0 - d) * (2000.0 - d) * 1e-27) * 1000.0, 1e-12);
  r.box_min.reset();
  EXPECT_THROW(scene_from_recipe(r, bundled_options()), InputError);  // nothing gives it a size
}

TEST(SceneFromRecipe, CopyNumberCheckNamesWhatIsMoreThanTenPercentOff) {
  ImportResult imported;
  imported.report.push_back({.ingredient = "hb", .region = "cell interior", .scene_region = "cell", .molecule = "hb",
                             .expected_copies = 1000, .measure = 0.5});
  imported.report.push_back({.ingredient = "igg", .region = "outside", .scene_region = "medium", .molecule = "igg",
                             .expected_copies = 200, .measure = 2.0});
  imported.report.push_back({.ingredient = "rare", .region = "cell surface", .scene_region = "cell", .molecule = "rare",
                             .expected_copies = 3, .measure = 0.1, .surface = true});
  int off = -1;
  std::string text = copy_number_check(imported, {{{"cell", "hb"}, 950.0}, {{"medium", "igg"}, 221.0}, {{"cell", "rare"}, 4.0}}, off);
  EXPECT_EQ(off, 1) << text;
  EXPECT_NE(text.find("hb [cell interior]: 950 of 1000 copies, 1900 of 2000 /µm³ (-5.0 %) ok"), std::string::npos) << text;
  EXPECT_NE(text.find("igg [outside]: 221 of 200 copies, 110.5 of 100 /µm³ (+10.5 %) OFF"), std::string::npos) << text;
  EXPECT_NE(text.find("rare [cell surface]: 4 of 3 copies, 40 of 30 /µm² (+33.3 %) ok"), std::string::npos) << text;  // one copy
  text = copy_number_check(imported, {}, off);  // nothing placed: every line off
  EXPECT_EQ(off, 3) << text;
  // The same for the bake's --report: asked and placed side by side.
  const HeldCopies held{{{"cell", "hb"}, 950.0}};
  const Json j = report_json(imported, &held);
  ASSERT_EQ(j.size(), 3u);
  EXPECT_EQ(j[0]["copies_asked"], 1000.0);
  EXPECT_EQ(j[0]["copies_placed"], 950.0);
  EXPECT_EQ(j[0]["volume_um3"], 0.5);
  EXPECT_EQ(j[2]["area_um2"], 0.1);
  EXPECT_EQ(j[1]["copies_placed"], 0.0);
  EXPECT_FALSE(report_json(imported, nullptr)[0].contains("copies_placed"));
}

TEST(SceneFromRecipe, RecipesAreToldFromScenes) {
  EXPECT_TRUE(is_cellpack_recipe(Json{{"recipe", {{"name", "x"}}}}));
  EXPECT_TRUE(is_cellpack_recipe(Json{{"format_version", "2.1"}}));
  EXPECT_FALSE(is_cellpack_recipe(Json{{"format", "nanouniverse-scene"}, {"recipe", 1}}));
  EXPECT_FALSE(is_cellpack_recipe(Json{{"molecules", Json::object()}}));
  EXPECT_FALSE(is_cellpack_recipe(Json::array({1, 2})));
}

}  // namespace
}  // namespace nano::cellpack
