#include "common/json_cursor.hpp"

#include <gtest/gtest.h>

#include "tests/scene/input_error_matchers.hpp"

namespace nano::scene {
namespace {

class JsonCursorTest : public ::testing::Test {
protected:
  const std::string file = "f.json";
  const Json doc = parse_json_text(R"({
    "obj": {"n": 2.5, "i": 16, "fi": 16.0, "neg": -3, "big": 18446744073709551615,
            "s": "text", "empty": "", "t": true, "v3": [1, 2, 3], "zero": [0, 0, 0], "v4": [1, 2, 3, 4], "axis": [0, 3, 4]},
    "list": [10, "x", {"deep": [1, 2]}]
  })", file);
  const JsonCursor root{doc, file};
  JsonCursor obj() const { return root.required("obj"); }
  JsonCursor at(const char* key) const { return obj().required(key); }
};

TEST_F(JsonCursorTest, PathsOfMembersAndElements) {
  EXPECT_EQ(root.path(), "");
  EXPECT_EQ(at("n").path(), "obj.n");
  const auto list = root.required("list").elements();
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[2].required("deep").elements()[1].path(), "list[2].deep[1]");
  EXPECT_EQ(list[0].file(), "f.json");
  EXPECT_EQ(list[0].json(), 10);
}

TEST_F(JsonCursorTest, RequiredOptionalHasAndMembers) {
  EXPECT_TRUE(obj().has("n"));
  EXPECT_FALSE(obj().has("nope"));
  EXPECT_FALSE(obj().optional("nope").has_value());
  EXPECT_EQ(obj().optional("s")->path(), "obj.s");
  EXPECT_INPUT_ERROR(obj().required("nope"), "obj.nope", "missing required key");
  EXPECT_INPUT_ERROR(at("n").required("x"), "obj.n", "expected an object, got a number 2.5");
  const auto members = root.members();
  ASSERT_EQ(members.size(), 2u);
  EXPECT_EQ(members[0].first, "obj");
  EXPECT_EQ(members[1].second.path(), "list");
}

TEST_F(JsonCursorTest, OnlyKeysNamesTheUnknownOne) {
  EXPECT_NO_THROW(root.only_keys({"obj", "list"}));
  EXPECT_INPUT_ERROR(root.only_keys({"obj"}), "list", "unknown key; allowed here: obj");
}

TEST_F(JsonCursorTest, Elements) {
  EXPECT_INPUT_ERROR(at("n").elements(), "obj.n", "expected an array");
  EXPECT_INPUT_ERROR(at("v3").elements(4), "obj.v3", "at least 4 elements, got 3");
  EXPECT_EQ(at("v3").elements(3).size(), 3u);
}

TEST_F(JsonCursorTest, Numbers) {
  EXPECT_EQ(at("n").number(), 2.5);
  EXPECT_INPUT_ERROR(at("s").number(), "obj.s", "expected a number, got \"text\"");
  EXPECT_INPUT_ERROR(at("t").number(), "obj.t", "expected a number, got true");
  EXPECT_EQ(at("n").number_at_least(2.5), 2.5);
  EXPECT_INPUT_ERROR(at("neg").number_at_least(0), "obj.neg", "expected a number >= 0, got -3");
  EXPECT_EQ(at("n").number_greater_than(2.0), 2.5);
  EXPECT_INPUT_ERROR(at("n").number_greater_than(2.5), "obj.n", "expected a number > 2.5, got 2.5");
  EXPECT_EQ(at("n").number_between(2.5, 3), 2.5);
  EXPECT_INPUT_ERROR(at("n").number_between(0, 1), "obj.n", "expected a number in [0, 1], got 2.5");
  EXPECT_EQ(at("n").number_strictly_between(2, 3), 2.5);
  EXPECT_INPUT_ERROR(at("n").number_strictly_between(2.5, 3), "obj.n", "expected a number in (2.5, 3), got 2.5");
}

TEST_F(JsonCursorTest, Integers) {
  EXPECT_EQ(at("i").integer_between(1, 16), 16);
  EXPECT_EQ(at("fi").integer_between(1, 16), 16);
  EXPECT_INPUT_ERROR(at("i").integer_between(1, 15), "obj.i", "expected an integer in [1, 15], got 16");
  EXPECT_INPUT_ERROR(at("n").integer_between(0, 10), "obj.n", "expected an integer in [0, 10], got 2.5");
  EXPECT_EQ(at("big").unsigned_integer(), 18446744073709551615ull);
  EXPECT_EQ(at("i").unsigned_integer(), 16u);
  EXPECT_INPUT_ERROR(at("neg").unsigned_integer(), "obj.neg", "got -3");
  EXPECT_INPUT_ERROR(at("n").unsigned_integer(), "obj.n", "got 2.5");
}

TEST_F(JsonCursorTest, BooleansAndStrings) {
  EXPECT_TRUE(at("t").boolean());
  EXPECT_INPUT_ERROR(at("s").boolean(), "obj.s", "expected true or false");
  EXPECT_EQ(at("s").string(), "text");
  EXPECT_INPUT_ERROR(at("i").string(), "obj.i", "expected a string, got a number 16");
  EXPECT_EQ(at("empty").string(), "");
  EXPECT_INPUT_ERROR(at("empty").non_empty_string(), "obj.empty", "non-empty");
}

TEST_F(JsonCursorTest, Vectors) {
  EXPECT_EQ(at("v3").vec3(), glm::dvec3(1, 2, 3));
  EXPECT_EQ(at("v3").non_zero_vec3(), glm::dvec3(1, 2, 3));
  EXPECT_EQ(at("axis").unit_vec3(), glm::dvec3(0, 0.6, 0.8));
  EXPECT_INPUT_ERROR(at("zero").unit_vec3(), "obj.zero", "non-zero");
  EXPECT_INPUT_ERROR(at("zero").non_zero_vec3(), "obj.zero", "non-zero");
  EXPECT_INPUT_ERROR(at("v4").vec3(), "obj.v4", "3 numbers");
  EXPECT_EQ(at("v4").vec4(), glm::dvec4(1, 2, 3, 4));
  EXPECT_INPUT_ERROR(at("v3").vec4(), "obj.v3", "4 numbers");
  EXPECT_INPUT_ERROR(root.required("list").elements()[2].required("deep").vec3(), "list[2].deep", "3 numbers");
}

TEST_F(JsonCursorTest, ShownShortensLongValues) {
  EXPECT_EQ(at("s").shown(), "\"text\"");
  const Json long_array = Json(std::vector<int>(100, 7));
  const std::string shown = JsonCursor(long_array, file).shown();
  EXPECT_EQ(shown.size(), 60u);
  EXPECT_EQ(shown.substr(57), "...");
}

TEST_F(JsonCursorTest, FailUsesThePath) {
  EXPECT_INPUT_ERROR(at("n").fail("custom rule"), "obj.n", "custom rule");
}

}  // namespace
}  // namespace nano::scene
