#include "common/json_document.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "bake/scene/scene_parser.hpp"
#include "tests/scene/input_error_matchers.hpp"

namespace nano::scene {
namespace {

// Wall-clock seconds `f` takes.
template <class F>
double seconds_for(F&& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The error `f` throws, its full message checked to start with "FILE:WHERE: " and to hold `rule_part`.
template <class F>
InputError expect_refusal(F&& f, const std::string& file, const std::string& where, const std::string& rule_part) {
  const InputError e = testing::expect_input_error(std::forward<F>(f));
  const std::string what = e.what();
  EXPECT_EQ(e.file(), file) << what.substr(0, 300);
  EXPECT_EQ(e.where(), where) << what.substr(0, 300);
  EXPECT_EQ(what.rfind(file + ":" + (where.empty() ? "" : where + ":") + " ", 0), 0u) << what.substr(0, 300);
  EXPECT_NE(e.rule().find(rule_part), std::string::npos) << what.substr(0, 300);
  return e;
}

// A scratch folder of its own per test, removed afterwards.
class TempDir {
public:
  explicit TempDir(const std::string& name) : path_(std::filesystem::temp_directory_path() / name) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }

private:
  std::filesystem::path path_;
};

TEST(JsonDocument, SyntaxErrorNamesLineAndColumn) {
  // The parser stumbles on the "}" that starts line 4, where a value was expected.
  const std::string text = "{\n  \"a\": 1,\n  \"b\": \n}\n";
  EXPECT_INPUT_ERROR(parse_json_text(text, "scene.json"), "4:1", "invalid JSON");
  const InputError e = testing::expect_input_error([&] { parse_json_text(text, "scene.json"); });
  EXPECT_EQ(e.file(), "scene.json");
  EXPECT_EQ(std::string(e.what()).rfind("scene.json:4:1: invalid JSON: ", 0), 0u) << e.what();
}

TEST(JsonDocument, SyntaxErrorOnFirstLine) {
  EXPECT_INPUT_ERROR(parse_json_text("[1, 2,, 3]", "s.json"), "1:7", "invalid JSON");
}

TEST(JsonDocument, DuplicateKeyNamesItsPath) {
  EXPECT_INPUT_ERROR(parse_json_text(R"({"a": {"b": 1, "b": 2}})", "s.json"), "a.b", "more than once");
  EXPECT_INPUT_ERROR(parse_json_text(R"({"x": [{"k": 1}, [3, {"k": 1, "k": 2}]]})", "s.json"), "x[1][1].k",
                     "more than once");
  EXPECT_INPUT_ERROR(parse_json_text(R"({"top": 1, "top": 1})", "s.json"), "top", "more than once");
}

TEST(JsonDocument, SameKeyInSiblingObjectsIsFine) {
  const Json j = parse_json_text(R"({"a": {"k": 1}, "b": {"k": 2}, "c": [{"k": 3}, {"k": 4}]})", "s.json");
  EXPECT_EQ(j["c"][1]["k"], 4);
}

TEST(JsonDocument, KeepsTheFileOrderOfKeys) {
  const Json j = parse_json_text(R"({"zebra": 1, "apple": 2, "mango": 3})", "s.json");
  std::vector<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.push_back(k);
  EXPECT_EQ(keys, (std::vector<std::string>{"zebra", "apple", "mango"}));
}

TEST(JsonDocument, ReadsAFileAndRejectsAMissingOne) {
  const auto dir = std::filesystem::temp_directory_path() / "nano_scene_json_document_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / "doc.json";
  std::ofstream(path) << R"({"seed": 5})";
  EXPECT_EQ(read_json_file(path)["seed"], 5);
  const InputError e = testing::expect_input_error([&] { read_json_file(dir / "absent.json"); });
  EXPECT_EQ(e.file(), (dir / "absent.json").string());
  EXPECT_NE(std::string(e.rule()).find("does not exist"), std::string::npos);
  std::filesystem::remove_all(dir);
}

// ---- Hostile input: every bound in json_document.hpp is refused quickly, with the file named.

TEST(JsonDocument, AMillionNestedArraysAreRefusedAtLevel65Fast) {
  const std::string text(1'000'000, '[');
  const double seconds = seconds_for([&] {
    expect_refusal([&] { parse_json_text(text, "deep.json"); }, "deep.json", "1:65", "JSON nested deeper than 64 levels");
  });
  EXPECT_LT(seconds, 1.0);
}

TEST(JsonDocument, AMillionNestedObjectsAreRefusedAtLevel65Fast) {
  std::string text;
  for (int i = 0; i < 1'000'000; ++i) text += "{\"a\":\n";
  const double seconds = seconds_for([&] {
    expect_refusal([&] { parse_json_text(text, "deep.json"); }, "deep.json", "65:1", "JSON nested deeper than 64 levels");
  });
  EXPECT_LT(seconds, 1.0);
}

TEST(JsonDocument, NestingExactlyAtTheLimitIsAccepted) {
  const std::string arrays = std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']');
  Json j = parse_json_text(arrays, "s.json");
  std::size_t depth = 0;
  for (const Json* v = &j; v->is_array(); v = v->empty() ? nullptr : &(*v)[0]) {
    ++depth;
    if (v->empty()) break;
  }
  EXPECT_EQ(depth, kMaxJsonDepth);

  std::string objects;
  for (std::size_t i = 0; i < kMaxJsonDepth; ++i) objects += "{\"k\": ";
  objects += "1" + std::string(kMaxJsonDepth, '}');
  EXPECT_NO_THROW(parse_json_text(objects, "s.json"));
  // One level more is refused, at the bracket that opens it.
  EXPECT_INPUT_ERROR(parse_json_text("[" + arrays + "]", "s.json"), "1:65", "nested deeper than 64 levels");
}

TEST(JsonDocument, TheDepthErrorPointsAtTheBracketNotAtBracketsInStrings) {
  const std::string prefix = R"({"s": "[{\"[", "t": ["]"],)" "\n" R"(  "d": )";
  const std::string text = prefix + std::string(kMaxJsonDepth, '[');
  // The object is level 1, so the 64th '[' opens level 65; it stands on line 2.
  const std::size_t column = std::string(R"(  "d": )").size() + kMaxJsonDepth;
  EXPECT_INPUT_ERROR(parse_json_text(text, "s.json"), "2:" + std::to_string(column), "nested deeper than 64 levels");
}

TEST(JsonDocument, AStringLongerThanTheLimitNamesItsKeyPath) {
  const std::string name(30'000'000, 'x');
  const double seconds = seconds_for([&] {
    expect_refusal([&] { parse_json_text(R"({"molecules": {"m": {"file": ")" + name + R"("}}})", "big.json"); },
                   "big.json", "molecules.m.file", "a string of 30000000 bytes; strings may be at most 1048576 bytes (1 MiB)");
  });
  EXPECT_LT(seconds, 2.0);  // reading 30 MB, most of it
  const std::string just_over(kMaxJsonStringBytes + 1, 'y');
  EXPECT_INPUT_ERROR(parse_json_text(R"({"a": [1, {"b": 2}, ")" + just_over + R"("]})", "s.json"), "a[2]",
                     "a string of 1048577 bytes");
  const std::string at_limit(kMaxJsonStringBytes, 'y');
  EXPECT_EQ(parse_json_text(R"({"a": [")" + at_limit + R"("]})", "s.json")["a"][0].get<std::string>().size(),
            kMaxJsonStringBytes);
}

TEST(JsonDocument, AKeyLongerThanTheLimitNamesItsObject) {
  const std::string key(kMaxJsonStringBytes + 1, 'k');
  EXPECT_INPUT_ERROR(parse_json_text(R"({"a": {"ok": 1, ")" + key + R"(": 2}})", "s.json"), "a",
                     "a key of 1048577 bytes; keys may be at most 1048576 bytes");
}

TEST(JsonDocument, AFileLargerThanTheLimitIsRefusedBeforeItIsRead) {
  const TempDir dir("nano_json_document_size_test");
  // Sparse: 1 GiB of zeros that take no disk; reading it would take seconds and a gigabyte.
  const auto huge = dir.path() / "huge.json";
  std::ofstream(huge).close();
  std::filesystem::resize_file(huge, std::uintmax_t(1) << 30);
  const double seconds = seconds_for([&] {
    expect_refusal([&] { read_json_file(huge); }, huge.string(), "",
                   "the file is 1073741824 bytes (1024 MiB); a JSON document may be at most 67108864 bytes (64 MiB)");
  });
  EXPECT_LT(seconds, 1.0);
  const auto just_over = dir.path() / "over.json";
  std::ofstream(just_over).close();
  std::filesystem::resize_file(just_over, kMaxJsonFileBytes + 1);
  expect_refusal([&] { read_json_file(just_over); }, just_over.string(), "", "the file is 67108865 bytes");
}

TEST(JsonDocument, NumbersBeyondADoubleNameTheirKeyPath) {
  expect_refusal([] { parse_json_text(R"({"a": {"b": [1, 1e400]}})", "n.json"); }, "n.json", "a.b[1]",
                 "the number 1e400 is out of the range of a double");
  EXPECT_INPUT_ERROR(parse_json_text(R"({"a": -2.5e308})", "n.json"), "a", "the number -2.5e308 is out of the range");
  const std::string long_number = "1" + std::string(400, '0');
  EXPECT_INPUT_ERROR(parse_json_text("{\"x\": {\"y\": " + long_number + "}}", "n.json"), "x.y", "out of the range");
  // Alone, a number has no key path: its line and column stand instead.
  EXPECT_INPUT_ERROR(parse_json_text("\n  1e400", "n.json"), "2:7", "the number 1e400 is out of the range");
  // Underflow is harmless: the number becomes 0.
  EXPECT_EQ(parse_json_text(R"({"a": 1e-400})", "n.json")["a"].get<double>(), 0.0);
}

// A scene whose membrane's tile_size is `tile_size` (JSON text).
std::string scene_with_tile_size(const std::string& tile_size) {
  return R"({"format": "nanouniverse-scene", "version": 1,
    "molecules": {"p": {"file": "p.pdb"}},
    "membranes": {"m": {"tile_size": )" + tile_size + R"(, "lipids": {"molecule": "p", "area_per_lipid": 65, "leaflet_offset": 12}}},
    "compartments": {"c": {"mesh": {"generate": "sphere", "triangles": 100, "radius": 500}, "membrane": "m"}},
    "instances": [{"compartment": "c"}]})";
}

TEST(JsonDocument, InfiniteOrNaNNumbersNeverReachTheScene) {
  EXPECT_NO_THROW(parse_scene_description(parse_json_text(scene_with_tile_size("200"), "scene.json"), "scene.json"));
  // From the text: refused by the reader.
  EXPECT_INPUT_ERROR(parse_json_text(scene_with_tile_size("1e400"), "scene.json"), "membranes.m.tile_size",
                     "the number 1e400 is out of the range of a double");
  // A document built in memory can hold them; the scene parser refuses them by key path.
  for (const double bad : {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN()}) {
    Json doc = parse_json_text(scene_with_tile_size("200"), "scene.json");
    doc["membranes"]["m"]["tile_size"] = bad;
    EXPECT_INPUT_ERROR(parse_scene_description(doc, "scene.json"), "membranes.m.tile_size", "expected a number > 0");
    doc = parse_json_text(scene_with_tile_size("200"), "scene.json");
    doc["membranes"]["m"]["lipids"]["leaflet_offset"] = bad;
    EXPECT_INPUT_ERROR(parse_scene_description(doc, "scene.json"), "membranes.m.lipids.leaflet_offset",
                       "expected a number >= 0");
  }
}

// A valid scene with `molecule_up` as its molecule's "up" and `extra` as more top-level members.
SceneDescription scene_with(const std::string& molecule_up, const std::string& extra) {
  const std::string text = R"({"format": "nanouniverse-scene", "version": 1,
    "molecules": {"p": {"file": "p.pdb", "up": )" + molecule_up + R"(}},
    "membranes": {"m": {"tile_size": 200, "lipids": {"molecule": "p", "area_per_lipid": 65, "leaflet_offset": 12}}},
    "compartments": {"c": {"mesh": {"generate": "sphere", "triangles": 100, "radius": 500}, "membrane": "m"}},
    "instances": [{"compartment": "c"}])" + extra + "}";
  return parse_scene_description(parse_json_text(text, "scene.json"), "scene.json");
}

TEST(JsonDocument, DirectionsWrittenWithExtremeNumbersKeepTheirMeaning) {
  // Normalising [1e-200, 0, 0] or [1e300, 1e300, 0] naively under- or overflows (NaN or 0).
  EXPECT_EQ(*scene_with("[1e-200, 0, 0]", "").molecules[0].up_axis, glm::dvec3(1, 0, 0));
  EXPECT_EQ(*scene_with("[0, 3e300, 4e300]", "").molecules[0].up_axis, glm::dvec3(0, 0.6, 0.8));
  const SceneDescription s = scene_with("[0, 0, 1]", R"(, "effects": {
      "shadows": {"light_direction": [0, 5e-324, 0]},
      "clipping": {"planes": [[3e300, 0, 4e300, 5e300], [0, -2e-300, 0, 1e-300]]},
      "animation": {"proxy_motion": {"steady": {"spin_axis": [1e200, 0, 0], "spin_degrees_per_second": 1}}}},
    "camera": {"position": [0, 0, -1e300], "look_at": [0, 0, 1e300], "up": [0, 1e-300, 0]})");
  EXPECT_EQ(direction_slot(s.effects.parameters, effect_parameter(EffectId::shadows, "light_direction")), glm::vec3(0, 1, 0));
  EXPECT_EQ(s.effects.clipping->planes[0], glm::dvec4(0.6, 0, 0.8, 1));
  EXPECT_EQ(s.effects.clipping->planes[1], glm::dvec4(0, -1, 0, 0.5));
  EXPECT_EQ(s.effects.animation->steady->spin_axis, glm::dvec3(1, 0, 0));
  EXPECT_EQ(s.camera->up, glm::dvec3(0, 1, 0));
  // A rotation axis too: the same matrix as the axis written plainly.
  const auto rotated = [](const std::string& axis) {
    Json doc = parse_json_text(R"({"format": "nanouniverse-scene", "version": 1,
      "molecules": {"p": {"file": "p.pdb"}},
      "membranes": {"m": {"tile_size": 200, "lipids": {"molecule": "p", "area_per_lipid": 65, "leaflet_offset": 12}}},
      "compartments": {"c": {"mesh": {"generate": "sphere", "triangles": 100, "radius": 500}, "membrane": "m"}},
      "instances": [{"compartment": "c", "transform": {"rotate": {"axis": )" + axis + R"(, "degrees": 30}}}]})", "scene.json");
    return std::get<ExplicitInstance>(parse_scene_description(doc, "scene.json").instances[0]).transform;
  };
  EXPECT_EQ(rotated("[1e-300, 2e-300, 0]"), rotated("[1, 2, 0]"));
  EXPECT_EQ(rotated("[1e300, 2e300, 0]"), rotated("[1, 2, 0]"));
}

TEST(JsonDocument, SizesBeyondADoubleAreRefused) {
  EXPECT_INPUT_ERROR(scene_with("[0, 0, 1]", R"(, "effects": {"clipping": {"planes": [[1e-300, 0, 0, 1e300]]}})"),
                     "effects.clipping.planes[0]", "the plane's offset d / |n| is beyond a double");
  EXPECT_INPUT_ERROR(scene_with("[0, 0, 1]", R"(, "effects": {"clipping": {"box": [[-1e308, 0, 0], [1e308, 1, 1]]}})"),
                     "effects.clipping.box", "max - min overflows");
  EXPECT_INPUT_ERROR(scene_with("[0, 0, 1]", R"(, "camera": {"position": [1e308, 0, 0], "look_at": [-1e308, 0, 0]})"),
                     "camera.look_at", "look_at - position overflows a double");
}

TEST(JsonDocument, AnEmptyFileIsRefused) {
  EXPECT_INPUT_ERROR(parse_json_text("", "e.json"), "", "the file is empty; expected a JSON document");
  EXPECT_INPUT_ERROR(parse_json_text(" \n\t\r\n", "e.json"), "", "the file is empty");
  const TempDir dir("nano_json_document_empty_test");
  const auto empty = dir.path() / "empty.json";
  std::ofstream(empty).close();
  expect_refusal([&] { read_json_file(empty); }, empty.string(), "", "the file is empty");
}

TEST(JsonDocument, BinaryAndNonUtf8TextAreRefused) {
  // Latin-1 é inside a string: not UTF-8.
  EXPECT_INPUT_ERROR(parse_json_text("{\"name\": \"caf\xe9\"}", "t.json"), "1:15", "invalid JSON");
  EXPECT_INPUT_ERROR(parse_json_text("{\"name\": \"\xff\xfe\"}", "t.json"), "1:11", "ill-formed UTF-8");
  // Binary data: a NUL byte anywhere (nlohmann alone would stop reading at it, and accept
  // a valid document followed by a NUL and anything at all).
  EXPECT_INPUT_ERROR(parse_json_text(std::string("\x89PNG\r\n\x1a\n\0\0", 10), "t.json"), "3:1", "a NUL byte");
  EXPECT_INPUT_ERROR(parse_json_text(std::string("{\"a\": 1}\0garbage", 16), "t.json"), "1:9", "a NUL byte");
  EXPECT_INPUT_ERROR(parse_json_text("\x89PNG", "t.json"), "1:1", "invalid JSON");
  // UTF-16 with its byte-order mark.
  EXPECT_INPUT_ERROR(parse_json_text(std::string("\xff\xfe{\0}\0", 6), "t.json"), "1:4", "a NUL byte");
  EXPECT_INPUT_ERROR(parse_json_text("\xff\xfe", "t.json"), "1:1", "invalid JSON");
  // A UTF-8 byte-order mark is allowed, and so is UTF-8 in strings.
  EXPECT_EQ(parse_json_text("\xef\xbb\xbf{\"name\": \"caf\xc3\xa9\"}", "t.json")["name"], "caf\xc3\xa9");
}

TEST(JsonDocument, MoreValuesThanTheLimitAreRefused) {
  // The array itself is one value.
  std::string at_limit = "[0";
  for (std::size_t i = 2; i < kMaxJsonValues; ++i) at_limit += ",0";
  at_limit += "]";
  EXPECT_EQ(parse_json_text(at_limit, "v.json").size(), kMaxJsonValues - 1);
  at_limit.back() = ',';
  expect_refusal([&] { parse_json_text(at_limit + "0]", "v.json"); }, "v.json", "[" + std::to_string(kMaxJsonValues - 1) + "]",
                 "more than 4194304 values");
}

TEST(JsonDocument, LargeObjectsAreReadInLinearTime) {
  // ordered_json's own insertion searches the keys: 2·10^5 members would take seconds.
  constexpr int members = 200'000;
  std::string text = "{\"map\": {";
  for (int i = 0; i < members; ++i) text += (i ? ",\"k" : "\"k") + std::to_string(i) + "\": 0";
  Json j;
  EXPECT_LT(seconds_for([&] { j = parse_json_text(text + "}}", "big.json"); }), 1.0);
  EXPECT_EQ(j["map"].size(), std::size_t(members));
  EXPECT_EQ(j["map"]["k123456"], 0);
  // A repeated key in a large object is still found, the first repeat in file order named.
  EXPECT_INPUT_ERROR(parse_json_text(text + ", \"k99\": 1, \"k17\": 2}}", "big.json"), "map.k99",
                     "key \"k99\" appears more than once");
}

TEST(JsonDocument, ManyNamesAndReferencesAreResolvedInLinearTime) {
  // 10^5 compartments, and 10^5 instances naming the last: a linear search per name would be 10^10 steps.
  constexpr int count = 100'000;
  std::string text = R"({"format": "nanouniverse-scene", "version": 1, "molecules": {"p": {"file": "p.pdb"}},
    "membranes": {"m": {"tile_size": 200, "lipids": {"molecule": "p", "area_per_lipid": 65, "leaflet_offset": 12}}},
    "compartments": {)";
  for (int i = 0; i < count; ++i)
    text += (i ? ", \"c" : "\"c") + std::to_string(i) + R"(": {"mesh": {"generate": "rbc", "triangles": 300}, "membrane": "m"})";
  text += R"(}, "instances": [)";
  for (int i = 0; i < count; ++i) text += (i ? ", " : "") + std::string(R"({"compartment": "c99999"})");
  text += "]}";
  SceneDescription scene;
  EXPECT_LT(seconds_for([&] { scene = parse_scene_description(parse_json_text(text, "scene.json"), "scene.json"); }), 3.0);
  ASSERT_EQ(scene.instances.size(), std::size_t(count));
  EXPECT_EQ(std::get<ExplicitInstance>(scene.instances.back()).compartment, (NameRef{"c99999", count - 1}));
}

TEST(JsonDocument, LongNamesAreRefusedWithoutRepeatingThem) {
  // Names are part of every key path below them; a megabyte name would be copied into each.
  const std::string name(1'000'000, 'n');
  const InputError e = testing::expect_input_error([&] {
    parse_scene_description(parse_json_text(R"({"format": "nanouniverse-scene", "version": 1,
      "molecules": {")" + name + R"(": {"file": "p.pdb"}}, "compartments": {}, "instances": []})", "scene.json"), "scene.json");
  });
  EXPECT_EQ(e.where(), "molecules");
  EXPECT_NE(e.rule().find("has 1000000 characters; a name may have at most 100"), std::string::npos) << e.rule().substr(0, 200);
  EXPECT_LT(std::string(e.what()).size(), 300u);
}

}  // namespace
}  // namespace nano::scene
