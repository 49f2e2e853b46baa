// A complete scene.json parses into exactly the values written out by hand below.
#include "bake/scene/scene_parser.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "bake/scene/random_placement.hpp"
#include "tests/scene/input_error_matchers.hpp"

namespace nano::scene {
namespace {

constexpr const char* complete_scene = R"({
  "format": "nanouniverse-scene",
  "version": 1,
  "description": "every feature once",
  "seed": 42,
  "molecules": {
    "spike": {"file": "pdb/6vxx.pdb", "colour": "#ff8000", "up": [0, 0, 2]},
    "popc": {"file": "/data/popc.pdb", "colour": [0.5, 0.25, 1], "up": "principal", "hydrogens": false},
    "hb": {"file": "../shared/4hhb.pdb", "all_models": true, "keep_water": true}
  },
  "membranes": {
    "envelope": {
      "tile_size": 200,
      "proteins": [
        {"molecule": "spike", "density_per_um2": 1200, "depth": 45.5, "per_compartment": 25},
        {"molecule": "hb", "copies_per_tile": 0.5}
      ],
      "lipids": {"molecule": "popc", "area_per_lipid": 65, "leaflet_offset": 12}
    },
    "rbc_membrane": {"tile_size": 300.5, "edge_colours": 3, "tiles": 81,
                     "lipid_patch": {"file": "pdb/bilayer.pdb.gz", "name": "POPC", "colour": "#808080", "clearance": 0.7},
                     "lipid_mix": [{"file": "pdb/pope.pdb", "name": "POPE", "outer": 0.1, "inner": 0.75},
                                   {"file": "pdb/dopc.pdb", "name": "DOPC", "colour": "#000000", "outer": 0.5, "inner": 0.25}]}
  },
  "solubles": {
    "cytoplasm": {"cube_size": 250, "molecules": [{"molecule": "hb", "concentration_mM": 5.1}], "clearance": 15},
    "lumen": {"cube_size": 100, "face_colours": 2, "cubes": 8, "molecules": [{"molecule": "spike", "copies_per_um3": 3}]}
  },
  "compartments": {
    "virion": {"mesh": {"generate": "sphere", "triangles": 1280, "radius": 500}, "membrane": "envelope", "soluble": "lumen"},
    "cell": {"mesh": {"generate": "rbc", "triangles": 5000}, "membrane": "rbc_membrane", "soluble": "cytoplasm", "scale": 0.5},
    "blob": {"mesh": {"file": "meshes/blob.obj", "units": "nm", "diameter": 2000, "uv": "generate"}, "soluble": "cytoplasm"}
  },
  "instances": [
    {"compartment": "cell", "matrix": [[0, -1, 0, 100], [1, 0, 0, 200], [0, 0, 1, 300]]},
    {"compartment": "virion", "count": 3, "box": [[-1000, -1000, -1000], [1000, 1000, 1000]], "seed": 7, "min_gap": 20},
    {"compartment": "blob"},
    {"compartment": "virion", "count": 2, "box": [[0, 0, 0], [5000, 5000, 5000]]}
  ],
  "effects": {
    "clipping": {"planes": [[0, 0, 2, -4]], "box": [[-1, -2, -3], [4, 5, 6]]},
    "animation": {
      "proxy_motion": {"keyframes": [
        {"instance": 6, "keys": [{"time": 0}, {"time": 2.5, "matrix": [[2, 0, 0, 1], [0, 2, 0, 2], [0, 0, 2, 3]]}]}
      ]},
      "jitter": {"amplitude_degrees": 5, "frequency_hz": 2}
    },
    "ambient_occlusion": {"rays": 8, "radius": 30},
    "shadows": {"light_direction": [0, -3, 0]}
  },
  "camera": {"position": [0, 0, -5000], "look_at": [0, 0, 0], "fov_degrees": 60}
})";

const std::filesystem::path scene_path = "/scenes/demo/scene.json";

SceneDescription expected_scene() {
  SceneDescription s;
  s.source = scene_path;
  s.seed = 42;
  s.molecules = {
      {"spike", "/scenes/demo/pdb/6vxx.pdb", glm::dvec3(1.0, 128.0 / 255.0, 0.0), glm::dvec3(0, 0, 1), false, false, true},
      {"popc", "/data/popc.pdb", glm::dvec3(0.5, 0.25, 1.0), std::nullopt, false, false, false},
      {"hb", "/scenes/shared/4hhb.pdb", std::nullopt, std::nullopt, true, true, true},
  };
  const NameRef spike{"spike", 0}, popc{"popc", 1}, hb{"hb", 2};
  using SU = SurfaceAbundance::Unit;
  s.membranes = {
      {"envelope", 200.0, 2, 16,
       {{spike, {SU::per_um2, 1200.0}, 45.5, 25}, {hb, {SU::per_tile, 0.5}, 0.0}},
       LipidFill{popc, 65.0, 12.0}},
      {"rbc_membrane", 300.5, 3, 81, {}, std::nullopt,
       LipidPatchDescription{"POPC", "/scenes/demo/pdb/bilayer.pdb.gz", glm::dvec3(128.0 / 255.0), 0.7},
       {LipidPatchDescription{"POPE", "/scenes/demo/pdb/pope.pdb", std::nullopt, 0.6, 0.1, 0.75},
        LipidPatchDescription{"DOPC", "/scenes/demo/pdb/dopc.pdb", glm::dvec3(0.0), 0.6, 0.5, 0.25}}},
  };
  using VU = VolumeAbundance::Unit;
  s.solubles = {
      {"cytoplasm", 250.0, 2, 16, {{hb, {VU::millimolar, 5.1}}}, 15.0},
      {"lumen", 100.0, 2, 8, {{spike, {VU::per_um3, 3.0}}}, 0.0},
  };
  s.compartments = {
      {"virion", {MeshSource::Kind::sphere, {}, 1280, 500.0}, NameRef{"envelope", 0}, NameRef{"lumen", 1}, 1.0},
      {"cell", {MeshSource::Kind::rbc, {}, 5000, 0.0}, NameRef{"rbc_membrane", 1}, NameRef{"cytoplasm", 0}, 0.5},
      {"blob", {MeshSource::Kind::file, "/scenes/demo/meshes/blob.obj", 0, 0.0, 10.0, 2000.0, std::nullopt, MeshSource::Uv::generate},
       std::nullopt, NameRef{"cytoplasm", 0}, 1.0},
  };
  const NameRef virion{"virion", 0}, cell{"cell", 1}, blob{"blob", 2};
  s.instances = {
      ExplicitInstance{cell, {glm::dvec4(0, -1, 0, 100), glm::dvec4(1, 0, 0, 200), glm::dvec4(0, 0, 1, 300)}},
      RandomPlacement{virion, 3, {{-1000, -1000, -1000}, {1000, 1000, 1000}}, 7, 20.0},
      ExplicitInstance{blob, identity_transform()},
      // The derivation of an absent seed has its own oracle test (random_placement_test.cpp).
      RandomPlacement{virion, 2, {{0, 0, 0}, {5000, 5000, 5000}}, derive_placement_seed(42, 3), 0.0},
  };
  Animation animation;
  animation.keyframes = {{6,
                          {{0.0, identity_transform()},
                           {2.5, {glm::dvec4(2, 0, 0, 1), glm::dvec4(0, 2, 0, 2), glm::dvec4(0, 0, 2, 3)}}}}};
  const auto set = [&](EffectId id, std::string_view key, const glm::dvec3& value) {
    s.effects.plain[static_cast<std::size_t>(id)] = true;
    set_parameter(s.effects.parameters, effect_parameter(id, key), value);
  };
  set(EffectId::jitter, "amplitude_degrees", glm::dvec3(5.0, 0, 0));
  set(EffectId::jitter, "frequency_hz", glm::dvec3(2.0, 0, 0));
  s.effects.clipping = Clipping{{glm::dvec4(0, 0, 1, -2)}, Box{{-1, -2, -3}, {4, 5, 6}}};
  s.effects.animation = animation;
  set(EffectId::ambient_occlusion, "rays", glm::dvec3(8, 0, 0));
  set(EffectId::ambient_occlusion, "radius", glm::dvec3(30.0, 0, 0));
  set(EffectId::ambient_occlusion, "radius_pixels", glm::dvec3(0.0));  // the table's fallback
  set(EffectId::shadows, "light_direction", glm::dvec3(0, -1, 0));
  s.camera = Camera{{0, 0, -5000}, {0, 0, 0}, {0, 1, 0}, 60.0};
  return s;
}

TEST(SceneParser, CompleteSceneMatchesHandWrittenValues) {
  const SceneDescription actual = parse_scene_description(parse_json_text(complete_scene, "scene.json"), scene_path);
  const SceneDescription expected = expected_scene();
  // Section by section first, so that a failure points at the part that differs.
  EXPECT_EQ(actual.source, expected.source);
  EXPECT_EQ(actual.seed, expected.seed);
  ASSERT_EQ(actual.molecules.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(actual.molecules[i], expected.molecules[i]) << "molecule " << i;
  EXPECT_EQ(actual.membranes, expected.membranes);
  EXPECT_EQ(actual.solubles, expected.solubles);
  EXPECT_EQ(actual.compartments, expected.compartments);
  EXPECT_EQ(actual.instances, expected.instances);
  EXPECT_EQ(actual.effects.clipping, expected.effects.clipping);
  EXPECT_EQ(actual.effects.animation, expected.effects.animation);
  EXPECT_EQ(actual.effects.plain, expected.effects.plain);
  EXPECT_EQ(actual.effects.parameters, expected.effects.parameters);
  EXPECT_EQ(actual.camera, expected.camera);
  EXPECT_EQ(actual, expected);
}

TEST(SceneParser, MinimalSceneGetsTheDocumentedDefaults) {
  const SceneDescription s = parse_scene_description(parse_json_text(R"({
    "format": "nanouniverse-scene", "version": 1,
    "molecules": {"hb": {"file": "hb.pdb"}},
    "solubles": {"inside": {"cube_size": 80, "molecules": [{"molecule": "hb", "copies_per_um3": 1}]}},
    "compartments": {"c": {"mesh": {"file": "c.obj"}, "soluble": "inside"}},
    "instances": [{"compartment": "c"}]
  })", "s.json"), "relative/dir/s.json");
  EXPECT_EQ(s.seed, 0u);
  EXPECT_EQ(s.molecules[0], (MoleculeDescription{"hb", "relative/dir/hb.pdb", std::nullopt, std::nullopt, false, false, true}));
  EXPECT_EQ(s.solubles[0].face_colours, 2);
  EXPECT_EQ(s.solubles[0].cubes, 16);
  EXPECT_EQ(s.solubles[0].clearance, 0.0);
  EXPECT_EQ(s.compartments[0].scale, 1.0);
  EXPECT_FALSE(s.compartments[0].membrane.has_value());
  EXPECT_EQ(s.instances, (std::vector<InstanceEntry>{ExplicitInstance{{"c", 0}, identity_transform()}}));
  EXPECT_EQ(s.effects, Effects{});
  EXPECT_FALSE(s.camera.has_value());
}

TEST(SceneParser, TranslateRotateScaleInstance) {
  const SceneDescription s = parse_scene_description(parse_json_text(R"({
    "format": "nanouniverse-scene", "version": 1,
    "molecules": {"hb": {"file": "hb.pdb"}},
    "solubles": {"inside": {"cube_size": 80, "molecules": [{"molecule": "hb", "copies_per_um3": 1}]}},
    "compartments": {"c": {"mesh": {"file": "c.obj"}, "soluble": "inside"}},
    "instances": [{"compartment": "c", "transform": {"translate": [10, 20, 30], "rotate": {"axis": [0, 0, 1], "degrees": 90}, "scale": 2}},
                  {"compartment": "c", "transform": {"scale": 3}}]
  })", "s.json"), "s.json");
  // x -> 2y, y -> -2x, z -> 2z, then + (10, 20, 30).
  const Matrix3x4 expected = {glm::dvec4(0, -2, 0, 10), glm::dvec4(2, 0, 0, 20), glm::dvec4(0, 0, 2, 30)};
  const Matrix3x4& m = std::get<ExplicitInstance>(s.instances[0]).transform;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(m[r][c], expected[r][c], 1e-12);
  const Matrix3x4 scale3 = {glm::dvec4(3, 0, 0, 0), glm::dvec4(0, 3, 0, 0), glm::dvec4(0, 0, 3, 0)};
  EXPECT_EQ(std::get<ExplicitInstance>(s.instances[1]).transform, scale3);
}

TEST(SceneParser, LoadsFromDiskAndResolvesAgainstTheFilesFolder) {
  const auto dir = std::filesystem::temp_directory_path() / "nano_scene_parser_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "scene.json") << complete_scene;
  const SceneDescription s = load_scene_description(dir / "scene.json");
  EXPECT_EQ(s.source, dir / "scene.json");
  EXPECT_EQ(s.molecules[0].file, dir / "pdb" / "6vxx.pdb");
  EXPECT_EQ(s.molecules[2].file, (dir.parent_path() / "shared" / "4hhb.pdb"));
  EXPECT_EQ(s.compartments[2].mesh.file, dir / "meshes" / "blob.obj");
  EXPECT_INPUT_ERROR(load_scene_description(dir / "missing.json"), "", "does not exist");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace nano::scene

namespace nano::scene {
namespace {

// The complete example in docs/scene.md (its first ```json block) stays valid and placeable.
TEST(SceneParser, DocumentationExampleParses) {
  const std::filesystem::path doc_path = std::filesystem::path(NANO_SOURCE_DIR) / "docs" / "scene.md";
  std::ifstream in(doc_path);
  ASSERT_TRUE(in) << doc_path;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t start = text.find("```json\n");
  ASSERT_NE(start, std::string::npos);
  const std::size_t end = text.find("```", start + 8);
  const std::string example = text.substr(start + 8, end - start - 8);
  const SceneDescription s = parse_scene_description(parse_json_text(example, "docs/scene.md"), "scenes/demo/scene.json");
  EXPECT_EQ(s.molecules.size(), 5u);
  EXPECT_EQ(s.compartments.size(), 3u);
  EXPECT_EQ(expanded_instance_count(s), 22u);
  // Radii: virion 500 Å + spikes, cell 3.91 µm, custom blob 1 µm after its scale.
  EXPECT_EQ(expand_random_instances(s, {650.0, 39100.0, 10000.0}).size(), 22u);
}

}  // namespace
}  // namespace nano::scene

namespace nano::scene {
namespace {

MeshSource mesh_with(const std::string& remesh_member) {
  const std::string text = R"({
    "format": "nanouniverse-scene", "version": 1,
    "molecules": {"hb": {"file": "hb.pdb"}},
    "solubles": {"inside": {"cube_size": 80, "molecules": [{"molecule": "hb", "copies_per_um3": 1}]}},
    "compartments": {"c": {"mesh": {"file": "c.obj")" + remesh_member + R"(}, "soluble": "inside"}},
    "instances": [{"compartment": "c"}]
  })";
  return parse_scene_description(parse_json_text(text, "s.json"), "s.json").compartments[0].mesh;
}

TEST(SceneParser, RemeshIsAutomaticUnlessTheSceneSaysOffOrAnEdge) {
  EXPECT_EQ(mesh_with("").remesh, MeshSource::Remesh::automatic);
  EXPECT_EQ(mesh_with(R"(, "remesh": "auto")").remesh, MeshSource::Remesh::automatic);
  EXPECT_EQ(mesh_with(R"(, "remesh": "off")").remesh, MeshSource::Remesh::off);
  const MeshSource edge = mesh_with(R"(, "remesh": {"edge": 25.5})");
  EXPECT_EQ(edge.remesh, MeshSource::Remesh::edge);
  EXPECT_EQ(edge.remesh_edge, 25.5);
}

}  // namespace
}  // namespace nano::scene
