// The cellPACK recipe reader on recipes of cellPACK's own repositories (tests/cellpack/data, with
// their origin) and on small hand-written ones for each rule; expectations are read off the files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "bake/cellpack/recipe_reader.hpp"
#include "common/error.hpp"

namespace nano::cellpack {
namespace {

namespace fs = std::filesystem;

const fs::path kData = fs::path(NANO_SOURCE_DIR) / "tests/cellpack/data";

// A scratch folder per test, with files written into it.
class RecipeFolder : public ::testing::Test {
protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / (std::string("nano_cellpack_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p;
  }
  fs::path dir_;
};

// The error read_recipe throws for `file`, or "" when it reads.
std::string error_of(const fs::path& file, const RecipeReadOptions& options = {}) {
  try {
    read_recipe(file, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const Ingredient* find(const std::vector<Ingredient>& list, const std::string& id) {
  for (const Ingredient& i : list)
    if (i.id == id) return &i;
  return nullptr;
}

TEST(CellpackV2, NestedSpheresReadAsCellpackDefinesThem) {
  const Recipe r = read_recipe(kData / "nested_spheres.json");
  EXPECT_EQ(r.format, RecipeFormat::v2);
  EXPECT_EQ(r.name, "nested_spheres");
  EXPECT_EQ(r.version, "2.0");
  ASSERT_TRUE(r.box_min && r.box_max);
  EXPECT_EQ(*r.box_min, glm::dvec3(-1000));
  EXPECT_EQ(*r.box_max, glm::dvec3(1000));
  // The root (bounding_area) lists outer_sphere and 5 green spheres outside every container.
  ASSERT_EQ(r.outside.size(), 1u);
  EXPECT_EQ(r.outside[0].id, "green_sphere");
  EXPECT_EQ(r.outside[0].count, 5u);
  EXPECT_EQ(r.outside[0].encapsulating_radius, 30.0);  // inherited type, own radius
  EXPECT_EQ(r.outside[0].type, "single_sphere");       // from common_settings
  ASSERT_TRUE(r.outside[0].colour);
  EXPECT_NEAR(r.outside[0].colour->y, 0.70, 1e-12);
  ASSERT_EQ(r.compartments.size(), 2u);
  const Compartment& outer = r.compartments[0];
  EXPECT_EQ(outer.id, "outer_sphere");
  EXPECT_EQ(outer.parent, "");
  EXPECT_EQ(outer.geometry, Compartment::Geometry::sphere);
  EXPECT_EQ(outer.radius, 600.0);
  ASSERT_EQ(outer.interior.size(), 1u);
  EXPECT_EQ(outer.interior[0].id, "red_sphere");
  EXPECT_EQ(outer.interior[0].count, 40u);
  ASSERT_EQ(outer.surface.size(), 1u);
  EXPECT_EQ(outer.surface[0].count, 40u);
  const Compartment& inner = r.compartments[1];
  EXPECT_EQ(inner.id, "inner_sphere");
  EXPECT_EQ(inner.parent, "outer_sphere");
  EXPECT_EQ(inner.radius, 100.0);
  ASSERT_EQ(inner.interior.size(), 1u);
  EXPECT_EQ(inner.interior[0].count, 20u);
}

TEST(CellpackV2, MeshContainersAndGradientsOfPeroxisome) {
  const Recipe r = read_recipe(kData / "peroxisome.json");
  EXPECT_EQ(r.version, "2.1");
  ASSERT_EQ(r.compartments.size(), 2u);
  EXPECT_EQ(r.compartments[0].id, "membrane");
  EXPECT_EQ(r.compartments[0].geometry, Compartment::Geometry::mesh);
  EXPECT_EQ(r.compartments[0].mesh_file, "mem_mesh_743916.obj");
  EXPECT_EQ(r.compartments[1].id, "nucleus");
  EXPECT_EQ(r.compartments[1].parent, "membrane");
  const Ingredient* peroxisome = find(r.compartments[0].interior, "peroxisome");
  ASSERT_NE(peroxisome, nullptr);
  EXPECT_EQ(peroxisome->count, 59u);
  // Its gradient is named as not carried over, and so are the recipe's gradients.
  ASSERT_FALSE(peroxisome->not_carried.empty());
  EXPECT_NE(peroxisome->not_carried[0].find("gradient"), std::string::npos);
  ASSERT_FALSE(r.not_carried.empty());
  EXPECT_NE(r.not_carried[0].find("gradients"), std::string::npos);
}

TEST_F(RecipeFolder, V1IncludeFromTheServerFolderWithItsValues) {
  // The HIV envelope protein of cellPACK's database, included by its server path.
  fs::create_directories(dir_ / "server/recipes");
  fs::copy_file(kData / "HIV1_ENV_4nco_0_1_4.json", dir_ / "server/recipes/HIV1_ENV_4nco_0_1_4.json");
  const fs::path recipe = write("hiv.json", R"({"recipe": {"name": "env", "version": "1.0"},
    "options": {"boundingBox": [[-725, -725, -834.29], [881.659, 1087.89, 725]]},
    "compartments": {"envelope": {"geom": "autoPACKserver/geometries/envelope.dae",
      "surface": {"ingredients": {"HIV1_ENV_4nco_0_1_1": {"include": "autoPACKserver/recipes/HIV1_ENV_4nco_0_1_4.json"}}}}}})");
  // Without the server folder, the include is named with every place tried.
  const std::string missing = error_of(recipe);
  EXPECT_NE(missing.find("HIV1_ENV_4nco_0_1_4.json' not found (tried"), std::string::npos) << missing;
  EXPECT_NE(missing.find("--server"), std::string::npos) << missing;
  RecipeReadOptions options;
  options.server_folder = dir_ / "server";
  const Recipe r = read_recipe(recipe, options);
  EXPECT_EQ(r.format, RecipeFormat::v1);
  EXPECT_EQ(r.version, "\"1.0\"");
  EXPECT_TRUE(r.outside.empty());  // no cytoplasme: allowed
  ASSERT_EQ(r.compartments.size(), 1u);
  EXPECT_EQ(r.compartments[0].geometry, Compartment::Geometry::mesh);
  EXPECT_EQ(r.compartments[0].mesh_file, "autoPACKserver/geometries/envelope.dae");
  ASSERT_EQ(r.compartments[0].surface.size(), 1u);
  const Ingredient& env = r.compartments[0].surface[0];
  EXPECT_EQ(env.id, "HIV1_ENV_4nco_0_1_1");  // the key, not the file's name
  EXPECT_EQ(env.molarity, 0.0031);
  EXPECT_EQ(env.count, 0u);
  EXPECT_EQ(*env.principal_vector, glm::dvec3(0, 0, -1));
  EXPECT_EQ(env.encapsulating_radius, 142.213);
  EXPECT_EQ(env.structure, "HIV1_ENV_4ncoABEFIJ.pdb");
  EXPECT_EQ(env.sphere_file, "autoPACKserver/collisionTrees/HIV1_ENV_4nco_0_1_1.sph");
  EXPECT_EQ(env.type, "MultiSphere");
  ASSERT_EQ(env.not_carried.size(), 1u);
  EXPECT_NE(env.not_carried[0].find("gradient gradRadSPIKE"), std::string::npos);
}

TEST_F(RecipeFolder, V1DatabaseRecipeNamesItsFirstMissingInclude) {
  fs::copy_file(kData / "HIV-1_0.1.6-7.json", dir_ / "HIV-1_0.1.6-7.json");
  const std::string e = error_of(dir_ / "HIV-1_0.1.6-7.json");
  EXPECT_NE(e.find("compartments.HIV1_envelope_Pack_145_0_2_0.surface.ingredients."), std::string::npos) << e;
  EXPECT_NE(e.find("not found (tried"), std::string::npos) << e;
}

TEST_F(RecipeFolder, V1InlineIngredientsOverwriteAndMesoscopeSpheres) {
  write("alb.json", R"({"Type": "MultiSphere", "molarity": 0.0006, "nbMol": 3, "pdb": "1AO6", "color": [200, 100, 50],
                        "radii": [[20, 30]], "positions": [[[0, 0, 0], [10, 0, 0]]]})");
  const fs::path recipe = write("plasma.json", R"({"recipe": {"name": "plasma", "version": "1.1"},
    "cytoplasme": {"ingredients": {
      "albumin": {"include": "alb.json", "overwrite": {"nbMol": 7}},
      "igg": {"Type": "MultiSphere", "molarity": "0.00007", "pdb": "None", "source": {"pdb": "1HZH", "transform": {"offset": [0, 0, 5]}},
              "radii": [{"radii": ["20", "25"]}], "positions": [{"coords": [0, 0, 0, 1, 2, 3]}],
              "partners_name": ["albumin"], "packingMode": "closePartner"},
      "dna": {"Type": "Grow", "nbMol": 2}}},
    "compartments": {"vesicle": {"geom_type": "mb", "geom": "mb", "mb": {"positions": [1, 2, 3], "radii": [600]}}}})");
  const Recipe r = read_recipe(recipe);
  ASSERT_EQ(r.outside.size(), 3u);
  const Ingredient& alb = r.outside[0];
  EXPECT_EQ(alb.count, 7u);  // the stub's overwrite wins
  EXPECT_EQ(alb.molarity, 0.0006);
  EXPECT_EQ(alb.structure, "1AO6");
  EXPECT_NEAR(alb.colour->x, 200.0 / 255.0, 1e-12);  // 0–255 scaled
  ASSERT_EQ(alb.spheres.size(), 2u);
  EXPECT_EQ(alb.spheres[1], glm::dvec4(10, 0, 0, 30));
  const Ingredient& igg = r.outside[1];
  EXPECT_EQ(igg.molarity, 0.00007);  // a number written as a string
  EXPECT_EQ(igg.structure, "1HZH");  // source.pdb over "None"
  EXPECT_EQ(*igg.offset, glm::dvec3(0, 0, 5));
  ASSERT_EQ(igg.spheres.size(), 2u);
  EXPECT_EQ(igg.spheres[1], glm::dvec4(1, 2, 3, 25));
  ASSERT_EQ(igg.not_carried.size(), 2u);
  EXPECT_NE(igg.not_carried[0].find("partners"), std::string::npos);
  EXPECT_NE(igg.not_carried[1].find("closePartner"), std::string::npos);
  ASSERT_EQ(r.outside[2].not_carried.size(), 1u);
  EXPECT_NE(r.outside[2].not_carried[0].find("fibre"), std::string::npos);
  ASSERT_EQ(r.compartments.size(), 1u);
  EXPECT_EQ(r.compartments[0].geometry, Compartment::Geometry::sphere);
  EXPECT_EQ(r.compartments[0].centre, glm::dvec3(1, 2, 3));
  EXPECT_EQ(r.compartments[0].radius, 600.0);
}

TEST_F(RecipeFolder, BadRecipesAreRefusedWithFileAndKey) {
  const auto v1 = [&](const std::string& name, const std::string& ingredient) {
    return write(name, R"({"recipe": {"name": "x"}, "cytoplasme": {"ingredients": {"a": )" + ingredient + "}}}");
  };
  EXPECT_NE(error_of(v1("neg.json", R"({"molarity": -0.1})")).find("neg.json:cytoplasme.ingredients.a.molarity: a molarity"),
            std::string::npos);
  EXPECT_NE(error_of(v1("huge.json", R"({"nbMol": 1e13})")).find("huge.json:cytoplasme.ingredients.a.nbMol: at most 10^12"),
            std::string::npos);
  EXPECT_NE(error_of(v1("frac.json", R"({"nbMol": 2.5})")).find("whole number"), std::string::npos);
  EXPECT_NE(error_of(v1("nan.json", R"({"principalVector": [0, "x", 1]})")).find("principalVector[1]: expected a number"),
            std::string::npos);
  // An include file is itself an ingredient: one that includes again is refused, so a cycle can only
  // run through the recipe itself.
  write("chained.json", R"({"include": "other.json"})");
  EXPECT_NE(error_of(v1("chain.json", R"({"include": "chained.json"})")).find("chained.json:include: an included ingredient file includes nothing further"),
            std::string::npos) << error_of(dir_ / "chain.json");
  const fs::path self = v1("self.json", R"({"include": "self.json"})");
  EXPECT_NE(error_of(self).find("includes itself"), std::string::npos) << error_of(self);
  write("v3.json", R"({"format_version": "3.0", "name": "x", "composition": {}})");
  EXPECT_NE(error_of(dir_ / "v3.json").find("unknown recipe format '3.0'"), std::string::npos);
  write("other.json", R"({"molecules": {}})");
  EXPECT_NE(error_of(dir_ / "other.json").find("not a cellPACK recipe"), std::string::npos);
  write("two_roots.json", R"({"format_version": "2.0", "name": "x", "objects": {"s": {"type": "single_sphere", "radius": 5}},
    "composition": {"a": {"regions": {"interior": [{"object": "s", "count": 1}]}}, "b": {"object": "s", "count": 2}}})");
  EXPECT_NE(error_of(dir_ / "two_roots.json").find("exactly one entry that no other lists"), std::string::npos);
  write("inherit.json", R"({"format_version": "2.1", "name": "x",
    "objects": {"s": {"inherit": "t", "radius": 5}, "t": {"inherit": "s"}},
    "composition": {"root": {"regions": {"interior": [{"object": "s", "count": 1}]}}}})");
  EXPECT_NE(error_of(dir_ / "inherit.json").find("inherit in a cycle"), std::string::npos) << error_of(dir_ / "inherit.json");
  write("unknown.json", R"({"format_version": "2.1", "name": "x", "objects": {},
    "composition": {"root": {"regions": {"interior": [{"object": "nope", "count": 1}]}}}})");
  EXPECT_NE(error_of(dir_ / "unknown.json").find("unknown object 'nope'"), std::string::npos);
  EXPECT_NE(error_of(dir_ / "absent.json").find("absent.json"), std::string::npos);
}

TEST(CellpackFiles, CandidatesForServerAndPlainNames) {
  RecipeReadOptions options;
  options.server_folder = "db";
  const auto server = recipe_file_candidates("autoPACKserver/recipes/a.json", "here", options);
  ASSERT_EQ(server.size(), 2u);
  EXPECT_EQ(server[0], fs::path("db/recipes/a.json"));
  EXPECT_EQ(server[1], fs::path("here/a.json"));
  const auto github = recipe_file_candidates("github:recipes/a.json", "here", {});
  ASSERT_EQ(github.size(), 1u);
  EXPECT_EQ(github[0], fs::path("here/a.json"));
  const auto plain = recipe_file_candidates("a.json", "here", options);
  ASSERT_EQ(plain.size(), 1u);
  EXPECT_EQ(plain[0], fs::path("here/a.json"));
  const auto sub = recipe_file_candidates("sub/a.json", "here", options);
  ASSERT_EQ(sub.size(), 2u);
  EXPECT_EQ(sub[0], fs::path("here/sub/a.json"));
  EXPECT_EQ(sub[1], fs::path("here/a.json"));
}

}  // namespace
}  // namespace nano::cellpack
