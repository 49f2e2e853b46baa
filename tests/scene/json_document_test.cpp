#include "bake/scene/json_document.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/scene/input_error_matchers.hpp"

namespace nano::scene {
namespace {

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

}  // namespace
}  // namespace nano::scene
