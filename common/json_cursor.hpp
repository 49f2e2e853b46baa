#pragma once
// Typed, checked access to one value of a JSON document that knows its own key path, so every
// rule broken by hand-written input is reported as nano::InputError("FILE", "a.b[2].c", "RULE").
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/error.hpp"
#include "common/json_document.hpp"

namespace nano {

class JsonCursor {
public:
  // The root of a document; `file` names it in error messages. Both must outlive the cursor.
  JsonCursor(const Json& root, const std::string& file) : value_(&root), file_(&file) {}

  const std::string& path() const { return path_; }
  const std::string& file() const { return *file_; }
  // This value as the source of a text parsed further (a camera spec inside a string).
  InputSource source() const { return {file(), path()}; }
  const Json& json() const { return *value_; }

  [[noreturn]] void fail(const std::string& rule) const;

  // Objects. `only_keys` rejects any member not in `allowed`, naming it and listing the allowed set.
  void only_keys(std::initializer_list<std::string_view> allowed) const;
  void only_keys(std::span<const std::string_view> allowed) const;
  bool has(std::string_view key) const;
  JsonCursor required(std::string_view key) const;
  std::optional<JsonCursor> optional(std::string_view key) const;
  std::vector<std::pair<std::string, JsonCursor>> members() const;

  // Arrays.
  std::vector<JsonCursor> elements(std::size_t min_count = 0) const;

  // Scalars. Ranges are inclusive unless the name says otherwise.
  double number() const;
  double number_at_least(double min) const;
  double number_greater_than(double min) const;
  double number_between(double min, double max) const;
  double number_strictly_between(double min, double max) const;
  std::int64_t integer_between(std::int64_t min, std::int64_t max) const;
  std::uint64_t unsigned_integer() const;  // the full 0 … 2^64−1 range (seeds)
  bool boolean() const;
  std::string string() const;
  std::string non_empty_string() const;

  // Fixed-size arrays of numbers.
  glm::dvec3 vec3() const;
  glm::dvec3 non_zero_vec3() const;
  glm::dvec3 unit_vec3() const;  // a non-zero vector divided by its length
  glm::dvec4 vec4() const;

  // The value as it appears in the file (shortened), for "got …" in messages.
  std::string shown() const;

private:
  JsonCursor(const Json& value, const std::string& file, std::string path)
      : value_(&value), file_(&file), path_(std::move(path)) {}
  JsonCursor child(std::string_view key) const;
  void expect_object() const;
  void expect_number(const std::string& expectation) const;

  const Json* value_;
  const std::string* file_;
  std::string path_;
};

}  // namespace nano
