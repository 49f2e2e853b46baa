// Every kind of bad scene.json is an InputError that names the exact key path.
#include <gtest/gtest.h>

#include <functional>

#include "bake/scene/scene_parser.hpp"
#include "tests/scene/input_error_matchers.hpp"

namespace nano::scene {
namespace {

// A small valid scene; each test breaks one thing in it.
Json valid_scene() {
  return parse_json_text(R"({
    "format": "nanouniverse-scene", "version": 1, "seed": 1,
    "molecules": {"spike": {"file": "s.pdb"}, "popc": {"file": "p.pdb"}, "hb": {"file": "h.pdb"}},
    "membranes": {"envelope": {"tile_size": 200,
                               "proteins": [{"molecule": "spike", "density_per_um2": 100}],
                               "lipids": {"molecule": "popc", "area_per_lipid": 65, "leaflet_offset": 12}}},
    "solubles": {"lumen": {"cube_size": 100, "molecules": [{"molecule": "hb", "concentration_mM": 1}]}},
    "compartments": {"virion": {"mesh": {"generate": "sphere", "triangles": 1000, "radius": 500},
                                "membrane": "envelope", "soluble": "lumen"}},
    "instances": [{"compartment": "virion", "transform": {"rotate": {"axis": [0, 0, 1], "degrees": 10}}},
                  {"compartment": "virion", "count": 2, "box": [[0, 0, 0], [9000, 9000, 9000]]}],
    "effects": {"clipping": {"planes": [[1, 0, 0, 0]]},
                "animation": {"jitter": {"amplitude_degrees": 5, "frequency_hz": 1}}},
    "camera": {"position": [0, 0, -10], "look_at": [0, 0, 0]}
  })", "scene.json");
}

void parse_modified(const std::function<void(Json&)>& modify) {
  Json doc = valid_scene();
  modify(doc);
  parse_scene_description(doc, "scene.json");
}

TEST(SceneErrors, TheBaseSceneIsValid) { EXPECT_NO_THROW(parse_modified([](Json&) {})); }

TEST(SceneErrors, MessageHasTheFileThePathAndTheRule) {
  const InputError e = testing::expect_input_error([] {
    parse_modified([](Json& d) { d["membranes"]["envelope"]["proteins"][0]["density_per_um2"] = "lots"; });
  });
  EXPECT_STREQ(e.what(), "scene.json:membranes.envelope.proteins[0].density_per_um2: expected a number >= 0, got \"lots\"");
}

// A patch of several kinds with the composition asked of each leaflet (data/rbc.json's form).
Json patch_of_kinds() {
  return parse_json_text(R"({"file": "rbc.pdb",
    "kinds": {"CHL1": {"name": "cholesterol", "colour": "#f0e060"}, "POPC": {}, "PSM": {"name": "SM"}},
    "leaflets": {"outer": {"mol_percent": {"cholesterol": 43, "POPC": 30, "SM": 27}, "area_per_lipid": 42},
                 "inner": {"mol_percent": {"cholesterol": 43, "POPC": 57}, "area_per_lipid": 44}}})", "scene.json");
}

// The base scene with `lipid_patch` (and its lipids fill removed), `change` applied to the patch.
Json scene_with_patch(const std::function<void(Json&)>& change) {
  Json d = valid_scene();
  d["membranes"]["envelope"].erase("lipids");
  Json patch = patch_of_kinds();
  change(patch);
  d["membranes"]["envelope"]["lipid_patch"] = patch;
  return d;
}

TEST(SceneErrors, APatchOfKindsParsesItsKindsAndLeaflets) {
  const SceneDescription s = parse_scene_description(scene_with_patch([](Json&) {}), "/scenes/scene.json");
  const LipidPatchDescription& p = *s.membranes.at(0).lipid_patch;
  ASSERT_EQ(p.kinds.size(), 3u);
  EXPECT_EQ(p.kinds[0].residue, "CHL1");
  EXPECT_EQ(p.kinds[0].name, "cholesterol");
  ASSERT_TRUE(p.kinds[0].colour.has_value());
  EXPECT_EQ(p.kinds[1].name, "POPC");  // a kind without a name reports under its residue name
  EXPECT_FALSE(p.kinds[1].colour.has_value());
  ASSERT_TRUE(p.outer_leaflet && p.inner_leaflet);
  EXPECT_EQ(p.outer_leaflet->mol_percent,
            (std::vector<std::pair<std::string, double>>{{"cholesterol", 43}, {"POPC", 30}, {"SM", 27}}));
  EXPECT_DOUBLE_EQ(p.outer_leaflet->area_per_lipid, 42);
  EXPECT_DOUBLE_EQ(p.inner_leaflet->area_per_lipid, 44);
}

TEST(SceneErrors, APatchOfKindsNamesWhatIsWrongInItsKindsAndLeaflets) {
  const auto parse_with = [](const std::function<void(Json&)>& change) {
    return parse_scene_description(scene_with_patch(change), "scene.json");
  };
  const std::string patch = "membranes.envelope.lipid_patch";
  EXPECT_INPUT_ERROR(parse_with([](Json& p) { p["name"] = "lipid"; }), patch + ".name", "each in \"kinds\"");
  EXPECT_INPUT_ERROR(parse_with([](Json& p) { p["colour"] = "#ffffff"; }), patch + ".colour", "each in \"kinds\"");
  EXPECT_INPUT_ERROR(parse_with([](Json& p) { p["kinds"]["POPC"]["name"] = "SM"; }), patch + ".kinds.PSM",
                     "two kinds report under the name 'SM'");
  EXPECT_INPUT_ERROR(parse_with([](Json& p) { p["kinds"]["TOOLONG"] = Json::object(); }), patch + ".kinds.TOOLONG",
                     "1 to 4 characters");
  EXPECT_INPUT_ERROR(parse_with([](Json& p) { p["kinds"] = Json::object(); }), patch + ".kinds", "at least one kind");
  EXPECT_INPUT_ERROR(parse_with([](Json& p) { p["leaflets"]["outer"]["mol_percent"]["chol"] = 0; }),
                     patch + ".leaflets.outer.mol_percent.chol", "no kind of this patch is named 'chol' (its kinds: 'cholesterol', 'POPC', 'SM')");
  EXPECT_INPUT_ERROR(parse_with([](Json& p) { p["leaflets"]["inner"]["mol_percent"]["POPC"] = 50; }),
                     patch + ".leaflets.inner.mol_percent", "add up to 93, not 100");
  EXPECT_INPUT_ERROR(parse_with([](Json& p) { p["leaflets"]["inner"]["mol_percent"]["POPC"] = -1; }),
                     patch + ".leaflets.inner.mol_percent.POPC", "");
  EXPECT_INPUT_ERROR(parse_with([](Json& p) { p["leaflets"]["inner"].erase("area_per_lipid"); }),
                     patch + ".leaflets.inner.area_per_lipid", "missing required key");
  EXPECT_INPUT_ERROR(parse_with([](Json& p) { p["leaflets"]["outer"]["area_per_lipid"] = 5; }),
                     patch + ".leaflets.outer.area_per_lipid", "");
  EXPECT_INPUT_ERROR(parse_with([](Json& p) { p["leaflets"].erase("inner"); }), patch + ".leaflets.inner",
                     "missing required key");
  EXPECT_INPUT_ERROR(parse_with([](Json& p) { p["leaflets"]["middle"] = Json::object(); }), patch + ".leaflets.middle",
                     "unknown key");
  // Without kinds the one kind is the patch's name.
  EXPECT_NO_THROW(parse_with([](Json& p) {
    p.erase("kinds");
    p["name"] = "POPC";
    p["leaflets"]["outer"]["mol_percent"] = Json{{"POPC", 100}};
    p["leaflets"]["inner"]["mol_percent"] = Json{{"POPC", 100}};
  }));
  EXPECT_INPUT_ERROR(parse_scene_description([] {
                       Json d = scene_with_patch([](Json&) {});
                       d["membranes"]["envelope"]["lipid_mix"] =
                           Json::array({Json{{"file", "e.pdb"}, {"name", "POPE"}, {"outer", 0.2}, {"inner", 0.2}}});
                       return d;
                     }(), "scene.json"),
                     "membranes.envelope.lipid_mix", "a patch of several kinds gives its composition");
}

TEST(SceneErrors, UnknownKeysAtEveryDepth) {
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["colour"] = 1; }), "colour", "unknown key; allowed here: format");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["membranes"]["envelope"]["thickness"] = 40; }),
                     "membranes.envelope.thickness", "unknown key");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["membranes"]["envelope"]["proteins"][0]["densty"] = 1; }),
                     "membranes.envelope.proteins[0].densty", "unknown key");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["instances"][0]["transform"]["rotate"]["angle"] = 1; }),
                     "instances[0].transform.rotate.angle", "allowed here: axis, degrees");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["effects"]["animation"]["jitter"]["phase"] = 0; }),
                     "effects.animation.jitter.phase", "unknown key");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["compartments"]["virion"]["mesh"]["file"] = "x.obj"; }),
                     "compartments.virion.mesh", "exactly one of \"file\" and \"generate\"");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) {
                       d["compartments"]["virion"]["mesh"] = Json{{"generate", "rbc"}, {"triangles", 900}, {"radius", 5}};
                     }),
                     "compartments.virion.mesh.radius", "unknown key");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["instances"][1]["transform"] = Json::object(); }),
                     "instances[1].transform", "allowed here: compartment, count, box, seed, min_gap");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["camera"]["zoom"] = 2; }), "camera.zoom", "unknown key");
}

TEST(SceneErrors, WrongTypes) {
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["membranes"]["envelope"]["tile_size"] = "big"; }),
                     "membranes.envelope.tile_size", "expected a number > 0, got \"big\"");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["molecules"]["spike"]["all_models"] = "yes"; }),
                     "molecules.spike.all_models", "expected true or false");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["instances"] = Json::object(); }), "instances", "expected an array");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["molecules"] = Json::array(); }), "molecules", "expected an object");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["molecules"]["spike"]["file"] = 3; }), "molecules.spike.file",
                     "expected a string");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["seed"] = -1; }), "seed", "expected an integer");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["instances"][1]["count"] = 2.5; }), "instances[1].count",
                     "expected an integer");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["molecules"]["spike"]["up"] = "vertical"; }),
                     "molecules.spike.up", "expected \"principal\" or [x, y, z]");
}

TEST(SceneErrors, OutOfRangeValues) {
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["membranes"]["envelope"]["tile_size"] = 0; }),
                     "membranes.envelope.tile_size", "expected a number > 0, got 0");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["membranes"]["envelope"]["proteins"][0]["density_per_um2"] = -1; }),
                     "membranes.envelope.proteins[0].density_per_um2", "expected a number >= 0, got -1");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["camera"]["fov_degrees"] = 180; }), "camera.fov_degrees",
                     "expected a number in (0, 180), got 180");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["molecules"]["spike"]["colour"] = {1.5, 0, 0}; }),
                     "molecules.spike.colour[0]", "expected a number in [0, 1], got 1.5");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["molecules"]["spike"]["colour"] = "#12345g"; }),
                     "molecules.spike.colour", "#rrggbb");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["molecules"]["spike"]["up"] = {0, 0, 0}; }), "molecules.spike.up",
                     "non-zero");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["effects"]["clipping"]["planes"][0] = {0, 0, 0, 5}; }),
                     "effects.clipping.planes[0]", "normal");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["instances"][1]["box"][1][2] = 0; }), "instances[1].box",
                     "min < max on every axis");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["membranes"]["envelope"]["tiles"] = 17; }),
                     "membranes.envelope.tiles", "expected an integer in [4, 16], got 17");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["solubles"]["lumen"]["cubes"] = 7; }), "solubles.lumen.cubes",
                     "expected an integer in [8, 64], got 7");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["membranes"]["envelope"]["edge_colours"] = 5; }),
                     "membranes.envelope.edge_colours", "give \"tiles\" in [25, 625]");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["compartments"]["virion"]["mesh"]["triangles"] = 0; }),
                     "compartments.virion.mesh.triangles", "expected an integer in [1,");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["compartments"]["virion"]["scale"] = -1; }),
                     "compartments.virion.scale", "> 0");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["instances"][0]["transform"]["scale"] = 0; }),
                     "instances[0].transform.scale", "> 0");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["instances"][1]["min_gap"] = -5; }), "instances[1].min_gap", ">= 0");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) {
                       d["instances"][0] = Json{{"compartment", "virion"},
                                                {"matrix", {{-1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}}};
                     }),
                     "instances[0].matrix", "positive determinant");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) {
                       d["instances"][0] = Json{{"compartment", "virion"}, {"matrix", {{1, 0, 0, 0}, {0, 1, 0, 0}}}};
                     }),
                     "instances[0].matrix", "3 rows of 4 numbers");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["version"] = 2; }), "version", "unsupported version 2");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["format"] = "other"; }), "format", "expected \"nanouniverse-scene\"");
}

TEST(SceneErrors, UnresolvedReferencesNameThePathAndTheMissingName) {
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["compartments"]["virion"]["membrane"] = "envelop"; }),
                     "compartments.virion.membrane", "unknown membrane \"envelop\" (defined: envelope)");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["compartments"]["virion"]["soluble"] = "cytosol"; }),
                     "compartments.virion.soluble", "unknown soluble \"cytosol\"");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["membranes"]["envelope"]["proteins"][0]["molecule"] = "spik"; }),
                     "membranes.envelope.proteins[0].molecule", "unknown molecule \"spik\" (defined: spike, popc, hb)");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["membranes"]["envelope"]["lipids"]["molecule"] = "dppc"; }),
                     "membranes.envelope.lipids.molecule", "unknown molecule \"dppc\"");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["solubles"]["lumen"]["molecules"][0]["molecule"] = "n"; }),
                     "solubles.lumen.molecules[0].molecule", "unknown molecule \"n\"");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["instances"][1]["compartment"] = "cell"; }),
                     "instances[1].compartment", "unknown compartment \"cell\" (defined: virion)");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) {
                       d.erase("solubles");
                     }),
                     "compartments.virion.soluble", "unknown soluble \"lumen\" (none are defined)");
}

TEST(SceneErrors, MissingRequiredKeys) {
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d.erase("format"); }), "format", "missing required key");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d.erase("instances"); }), "instances", "missing required key");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["membranes"]["envelope"].erase("tile_size"); }),
                     "membranes.envelope.tile_size", "missing required key");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["compartments"]["virion"]["mesh"].erase("radius"); }),
                     "compartments.virion.mesh.radius", "missing required key");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["instances"][0].erase("compartment"); }),
                     "instances[0].compartment", "missing required key");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["instances"][1].erase("count"); }), "instances[1].count",
                     "missing required key");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["camera"].erase("position"); }), "camera.position",
                     "missing required key");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["membranes"]["envelope"]["lipids"].erase("leaflet_offset"); }),
                     "membranes.envelope.lipids.leaflet_offset", "missing required key");
}

TEST(SceneErrors, ExactlyOneAmountPerMolecule) {
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["membranes"]["envelope"]["proteins"][0]["copies_per_tile"] = 2; }),
                     "membranes.envelope.proteins[0]", "exactly one of \"density_per_um2\" and \"copies_per_tile\", got both");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["membranes"]["envelope"]["proteins"][0].erase("density_per_um2"); }),
                     "membranes.envelope.proteins[0]", "got neither");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["solubles"]["lumen"]["molecules"][0]["copies_per_um3"] = 2; }),
                     "solubles.lumen.molecules[0]", "exactly one of \"concentration_mM\" and \"copies_per_um3\", got both");
}

TEST(SceneErrors, MeshUnitsSizeAndUvs) {
  const auto with_mesh = [](Json mesh) { return [mesh](Json& d) { d["compartments"]["virion"]["mesh"] = mesh; }; };
  EXPECT_INPUT_ERROR(parse_modified(with_mesh(Json{{"file", "c.obj"}, {"units", "inch"}})), "compartments.virion.mesh.units",
                     "expected \"A\", \"nm\" or \"um\", got \"inch\"");
  EXPECT_INPUT_ERROR(parse_modified(with_mesh(Json{{"file", "c.obj"}, {"uv", "lscm"}})), "compartments.virion.mesh.uv",
                     "expected \"auto\", \"keep\" or \"generate\"");
  EXPECT_INPUT_ERROR(parse_modified(with_mesh(Json{{"file", "c.obj"}, {"diameter", 10}, {"volume", 10}})),
                     "compartments.virion.mesh", "\"diameter\" or \"volume\", not both");
  EXPECT_INPUT_ERROR(parse_modified(with_mesh(Json{{"file", "c.obj"}, {"diameter", -1}})), "compartments.virion.mesh.diameter",
                     "expected a number > 0");
  EXPECT_INPUT_ERROR(parse_modified(with_mesh(Json{{"generate", "sphere"}, {"triangles", 100}, {"radius", 5}, {"units", "nm"}})),
                     "compartments.virion.mesh.units", "unknown key");
  EXPECT_INPUT_ERROR(parse_modified(with_mesh(Json{{"file", "c.obj"}, {"repair", "yes"}})), "compartments.virion.mesh.repair",
                     "expected");
  EXPECT_INPUT_ERROR(parse_modified(with_mesh(Json{{"file", "c.obj"}, {"uv", "keep"}, {"repair", true}})),
                     "compartments.virion.mesh.repair", "loses its UVs");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) {
                       d["compartments"]["virion"]["mesh"] = Json{{"file", "c.obj"}, {"volume", 1e6}};
                       d["compartments"]["virion"]["scale"] = 2;
                     }),
                     "compartments.virion.scale", "not both");
}

TEST(SceneErrors, Remesh) {
  const auto with_mesh = [](Json mesh) { return [mesh](Json& d) { d["compartments"]["virion"]["mesh"] = mesh; }; };
  EXPECT_INPUT_ERROR(parse_modified(with_mesh(Json{{"file", "c.obj"}, {"remesh", "always"}})), "compartments.virion.mesh.remesh",
                     "expected \"auto\", \"off\" or {\"edge\": Å}, got \"always\"");
  EXPECT_INPUT_ERROR(parse_modified(with_mesh(Json{{"file", "c.obj"}, {"remesh", true}})), "compartments.virion.mesh.remesh",
                     "expected \"auto\", \"off\"");
  EXPECT_INPUT_ERROR(parse_modified(with_mesh(Json{{"file", "c.obj"}, {"remesh", Json{{"edge", 0}}}})),
                     "compartments.virion.mesh.remesh.edge", "expected a number > 0");
  EXPECT_INPUT_ERROR(parse_modified(with_mesh(Json{{"file", "c.obj"}, {"remesh", Json{{"egde", 20}}}})),
                     "compartments.virion.mesh.remesh.egde", "unknown key");
  EXPECT_INPUT_ERROR(parse_modified(with_mesh(Json{{"file", "c.obj"}, {"uv", "keep"}, {"remesh", Json{{"edge", 20}}}})),
                     "compartments.virion.mesh.remesh", "loses its UVs");
}

TEST(SceneErrors, StructuralRules) {
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) {
                       d["membranes"]["envelope"].erase("proteins");
                       d["membranes"]["envelope"].erase("lipids");
                     }),
                     "membranes.envelope", "needs \"proteins\", \"lipids\" or \"lipid_patch\"");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["membranes"]["envelope"]["lipid_patch"] = Json{{"file", "b.pdb"}}; }),
                     "membranes.envelope.lipid_patch", "not both");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) {
                       d["membranes"]["envelope"].erase("lipids");
                       d["membranes"]["envelope"]["lipid_patch"] = Json{{"file", "b.pdb"}, {"period", 60}};
                     }),
                     "membranes.envelope.lipid_patch.period", "unknown key");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) {
                       d["membranes"]["envelope"].erase("lipids");
                       d["membranes"]["envelope"]["lipid_patch"] = Json{{"file", "b.pdb"}, {"clearance", 3}};
                     }),
                     "membranes.envelope.lipid_patch.clearance", "");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) {
                       d["membranes"]["envelope"].erase("lipids");
                       d["membranes"]["envelope"]["lipid_patch"] = Json{{"name", "POPC"}};
                     }),
                     "membranes.envelope.lipid_patch.file", "missing required key");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) {
                       d["membranes"]["envelope"]["lipid_mix"] = Json::array({Json{{"file", "e.pdb"}, {"outer", 0.2}, {"inner", 0.2}}});
                     }),
                     "membranes.envelope.lipid_mix", "needs the \"lipid_patch\"");
  const auto with_mix = [](Json mix) {
    return parse_modified([mix](Json& d) {
      d["membranes"]["envelope"].erase("lipids");
      d["membranes"]["envelope"]["lipid_patch"] = Json{{"file", "b.pdb"}, {"name", "POPC"}};
      d["membranes"]["envelope"]["lipid_mix"] = mix;
    });
  };
  EXPECT_INPUT_ERROR(with_mix(Json::array({Json{{"file", "e.pdb"}, {"name", "POPE"}, {"outer", 0.7}, {"inner", 0.2}},
                                           Json{{"file", "f.pdb"}, {"name", "DOPC"}, {"outer", 0.4}, {"inner", 0.2}}})),
                     "membranes.envelope.lipid_mix[1]", "more than 1 in a leaflet");
  EXPECT_INPUT_ERROR(with_mix(Json::array({Json{{"file", "e.pdb"}, {"name", "POPE"}, {"outer", 1.5}, {"inner", 0.2}}})),
                     "membranes.envelope.lipid_mix[0].outer", "");
  EXPECT_INPUT_ERROR(with_mix(Json::array({Json{{"file", "e.pdb"}, {"name", "POPE"}, {"inner", 0.2}}})),
                     "membranes.envelope.lipid_mix[0].outer", "missing required key");
  EXPECT_INPUT_ERROR(with_mix(Json::array({Json{{"file", "e.pdb"}, {"name", "POPC"}, {"outer", 0.2}, {"inner", 0.2}}})),
                     "membranes.envelope.lipid_mix[0].name", "a name of its own");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) {
                       d["compartments"]["virion"].erase("membrane");
                       d["compartments"]["virion"].erase("soluble");
                     }),
                     "compartments.virion", "needs a \"membrane\", a \"soluble\" or both");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["instances"] = Json::array(); }), "instances", "at least 1 element");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["compartments"] = Json::object(); }), "compartments",
                     "at least one compartment");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["instances"][0]["matrix"] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}; }),
                     "instances[0]", "either \"transform\" or \"matrix\", not both");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["molecules"]["a.b"] = Json{{"file", "x.pdb"}}; }), "molecules.a.b",
                     "only letters, digits");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["compartments"]["virion"]["mesh"]["generate"] = "cube"; }),
                     "compartments.virion.mesh.generate", "expected \"sphere\", \"rbc\" or \"box\"");
}

TEST(SceneErrors, MalformedJsonNamesLineAndColumn) {
  const std::string text = "{\n  \"format\": \"nanouniverse-scene\",\n  \"version\": 1,,\n}";
  EXPECT_INPUT_ERROR(parse_json_text(text, "scene.json"), "3:16", "invalid JSON");
}

// A stand-in (spheres instead of a structure file) is either/or with "file", and each sphere checked.
TEST(SceneErrors, StandInsAreSpheresInsteadOfAFile) {
  const Json spheres = Json{{"from", "its encapsulating radius"}, {"spheres", Json::array({Json::array({0, 0, 0, 40})})}};
  Json doc = valid_scene();
  doc["molecules"]["hb"] = Json{{"stand_in", spheres}};
  const SceneDescription s = parse_scene_description(doc, "scene.json");
  const MoleculeDescription& hb = s.molecules[2];
  EXPECT_TRUE(hb.file.empty());
  EXPECT_EQ(hb.stand_in_spheres, (std::vector<glm::dvec4>{{0, 0, 0, 40}}));
  EXPECT_EQ(hb.stand_in_from, "its encapsulating radius");
  EXPECT_INPUT_ERROR(parse_modified([&](Json& d) { d["molecules"]["hb"]["stand_in"] = spheres; }), "molecules.hb",
                     "either a structure \"file\" or a \"stand_in\"");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["molecules"]["hb"] = Json::object(); }), "molecules.hb", "exactly one of them");
  const auto with_spheres = [](Json list) {
    return [list](Json& d) { d["molecules"]["hb"] = Json{{"stand_in", {{"from", "x.sph"}, {"spheres", list}}}}; };
  };
  EXPECT_INPUT_ERROR(parse_modified(with_spheres(Json::array())), "molecules.hb.stand_in.spheres", "at least 1");
  EXPECT_INPUT_ERROR(parse_modified(with_spheres(Json::array({Json::array({0, 0, 0, 0})}))), "molecules.hb.stand_in.spheres[0]",
                     "radius must be in (0, 1000]");
  EXPECT_INPUT_ERROR(parse_modified(with_spheres(Json::array({Json::array({2e4, 0, 0, 5})}))), "molecules.hb.stand_in.spheres[0]",
                     "more than 10⁴ Å");
  EXPECT_INPUT_ERROR(parse_modified(with_spheres(Json::array({Json::array({0, 0, 5})}))), "molecules.hb.stand_in.spheres[0]", "");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["molecules"]["hb"] = Json{{"stand_in", {{"spheres", Json::array({Json::array({0, 0, 0, 1})})}}}}; }),
                     "molecules.hb.stand_in.from", "");
}

// A generated box: its three sides, each > 0; no triangle count to give.
TEST(SceneErrors, AGeneratedBoxIsItsSides) {
  Json doc = valid_scene();
  doc["compartments"]["virion"]["mesh"] = Json{{"generate", "box"}, {"size", {700, 1200, 2200}}};
  const SceneDescription s = parse_scene_description(doc, "scene.json");
  EXPECT_EQ(s.compartments[0].mesh.kind, MeshSource::Kind::box);
  EXPECT_EQ(s.compartments[0].mesh.box_size, glm::dvec3(700, 1200, 2200));
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["compartments"]["virion"]["mesh"] = Json{{"generate", "box"}, {"size", {700, 0, 1}}}; }),
                     "compartments.virion.mesh.size", "each side must be > 0");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) {
                       d["compartments"]["virion"]["mesh"] = Json{{"generate", "box"}, {"size", {1, 1, 1}}, {"triangles", 12}};
                     }),
                     "compartments.virion.mesh.triangles", "unknown key");
  EXPECT_INPUT_ERROR(parse_modified([](Json& d) { d["compartments"]["virion"]["mesh"] = Json{{"generate", "cube"}, {"size", {1, 1, 1}}}; }),
                     "compartments.virion.mesh.generate", "\"sphere\", \"rbc\" or \"box\"");
}

}  // namespace
}  // namespace nano::scene
