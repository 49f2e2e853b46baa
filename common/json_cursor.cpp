#include "common/json_cursor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <glm/geometric.hpp>

#include "common/error.hpp"

namespace nano {
namespace {

std::string format_number(double v) {
  std::ostringstream s;
  s.precision(std::numeric_limits<double>::max_digits10);
  s << v;
  return s.str();
}

// The same vector scaled by the power of two that brings its largest component into [1, 2).
// Exact, so whatever is normalised from it has the bits it had from `v` (when that did not
// overflow), yet one written as [1e-200, 0, 0] or [1e300, 1e300, 0] no longer under- or overflows.
glm::dvec3 rescaled(const glm::dvec3& v) {
  const int e = std::ilogb(std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}));
  return {std::ldexp(v.x, -e), std::ldexp(v.y, -e), std::ldexp(v.z, -e)};
}

std::string type_name(const Json& v) {
  if (v.is_object()) return "an object";
  if (v.is_array()) return "an array";
  if (v.is_string()) return "a string";
  if (v.is_boolean()) return "a boolean";
  if (v.is_null()) return "null";
  return "a number";
}

}  // namespace

void JsonCursor::fail(const std::string& rule) const { throw InputError(*file_, path_, rule); }

std::string JsonCursor::shown() const {
  constexpr std::size_t max_length = 60;
  std::string text = value_->dump();
  if (text.size() > max_length) text = text.substr(0, max_length - 3) + "...";
  return text;
}

JsonCursor JsonCursor::child(std::string_view key) const {
  const std::string child_path = path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  return JsonCursor(value_->at(std::string(key)), *file_, child_path);
}

void JsonCursor::expect_object() const {
  if (!value_->is_object()) fail("expected an object, got " + type_name(*value_) + " " + shown());
}

void JsonCursor::only_keys(std::initializer_list<std::string_view> allowed) const {
  only_keys(std::span<const std::string_view>(allowed.begin(), allowed.size()));
}

void JsonCursor::only_keys(std::span<const std::string_view> allowed) const {
  expect_object();
  for (const auto& [key, value] : value_->items()) {
    bool known = false;
    for (std::string_view a : allowed) known = known || a == key;
    if (known) continue;
    std::string list;
    for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    const std::string where = path_.empty() ? key : path_ + "." + key;
    throw InputError(*file_, where, "unknown key; allowed here: " + list);
  }
}

bool JsonCursor::has(std::string_view key) const {
  expect_object();
  return value_->contains(std::string(key));
}

JsonCursor JsonCursor::required(std::string_view key) const {
  if (!has(key)) {
    const std::string where = path_.empty() ? std::string(key) : path_ + "." + std::string(key);
    throw InputError(*file_, where, "missing required key");
  }
  return child(key);
}

std::optional<JsonCursor> JsonCursor::optional(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return child(key);
}

std::vector<std::pair<std::string, JsonCursor>> JsonCursor::members() const {
  expect_object();
  std::vector<std::pair<std::string, JsonCursor>> out;
  // From the member itself, not child(key): ordered_json finds a key by a linear search, which
  // would make a map of n names cost n².
  for (const auto& [key, value] : value_->items())
    out.emplace_back(key, JsonCursor(value, *file_, path_.empty() ? key : path_ + "." + key));
  return out;
}

std::vector<JsonCursor> JsonCursor::elements(std::size_t min_count) const {
  if (!value_->is_array()) fail("expected an array, got " + type_name(*value_) + " " + shown());
  if (value_->size() < min_count)
    fail("expected an array of at least " + std::to_string(min_count) + " element" +
         (min_count == 1 ? "" : "s") + ", got " + std::to_string(value_->size()));
  std::vector<JsonCursor> out;
  for (std::size_t i = 0; i < value_->size(); ++i)
    out.push_back(JsonCursor((*value_)[i], *file_, path_ + "[" + std::to_string(i) + "]"));
  return out;
}

void JsonCursor::expect_number(const std::string& expectation) const {
  // JSON cannot spell NaN or infinity, but a parser may still hand over an overflowed value.
  if (!value_->is_number() || !std::isfinite(value_->get<double>()))
    fail("expected " + expectation + ", got " + shown());
}

double JsonCursor::number() const {
  expect_number("a number");
  return value_->get<double>();
}

double JsonCursor::number_at_least(double min) const {
  const std::string expectation = "a number >= " + format_number(min);
  expect_number(expectation);
  const double v = value_->get<double>();
  if (!(v >= min)) fail("expected " + expectation + ", got " + shown());
  return v;
}

double JsonCursor::number_greater_than(double min) const {
  const std::string expectation = "a number > " + format_number(min);
  expect_number(expectation);
  const double v = value_->get<double>();
  if (!(v > min)) fail("expected " + expectation + ", got " + shown());
  return v;
}

double JsonCursor::number_between(double min, double max) const {
  const std::string expectation = "a number in [" + format_number(min) + ", " + format_number(max) + "]";
  expect_number(expectation);
  const double v = value_->get<double>();
  if (!(v >= min && v <= max)) fail("expected " + expectation + ", got " + shown());
  return v;
}

double JsonCursor::number_strictly_between(double min, double max) const {
  const std::string expectation = "a number in (" + format_number(min) + ", " + format_number(max) + ")";
  expect_number(expectation);
  const double v = value_->get<double>();
  if (!(v > min && v < max)) fail("expected " + expectation + ", got " + shown());
  return v;
}

std::int64_t JsonCursor::integer_between(std::int64_t min, std::int64_t max) const {
  const std::string expectation = "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
  expect_number(expectation);
  const double v = value_->get<double>();
  // Written as 16.0 is still the integer 16; 2.5 is not.
  if (v != std::floor(v) || v < static_cast<double>(min) || v > static_cast<double>(max))
    fail("expected " + expectation + ", got " + shown());
  if (value_->is_number_integer()) return value_->get<std::int64_t>();
  return static_cast<std::int64_t>(v);
}

std::uint64_t JsonCursor::unsigned_integer() const {
  const std::string expectation = "an integer in [0, 18446744073709551615]";
  if (value_->is_number_unsigned()) return value_->get<std::uint64_t>();
  if (value_->is_number_integer() && value_->get<std::int64_t>() >= 0)
    return static_cast<std::uint64_t>(value_->get<std::int64_t>());
  fail("expected " + expectation + ", got " + shown());
}

bool JsonCursor::boolean() const {
  if (!value_->is_boolean()) fail("expected true or false, got " + shown());
  return value_->get<bool>();
}

std::string JsonCursor::string() const {
  if (!value_->is_string()) fail("expected a string, got " + type_name(*value_) + " " + shown());
  return value_->get<std::string>();
}

std::string JsonCursor::non_empty_string() const {
  std::string s = string();
  if (s.empty()) fail("expected a non-empty string");
  return s;
}

glm::dvec3 JsonCursor::vec3() const {
  if (!value_->is_array() || value_->size() != 3) fail("expected an array of 3 numbers [x, y, z], got " + shown());
  const auto e = elements();
  return {e[0].number(), e[1].number(), e[2].number()};
}

glm::dvec3 JsonCursor::non_zero_vec3() const {
  const glm::dvec3 v = vec3();
  if (v == glm::dvec3(0.0)) fail("expected a non-zero vector, got " + shown());
  return v;
}

glm::dvec3 JsonCursor::unit_vec3() const {
  const glm::dvec3 v = rescaled(non_zero_vec3());
  // Division, not glm::normalize's multiplication by an inverse square root, so that an axis
  // such as [0, 3, 4] becomes exactly [0, 0.6, 0.8].
  return v / glm::length(v);
}

glm::dvec4 JsonCursor::vec4() const {
  if (!value_->is_array() || value_->size() != 4) fail("expected an array of 4 numbers, got " + shown());
  const auto e = elements();
  return {e[0].number(), e[1].number(), e[2].number(), e[3].number()};
}

}  // namespace nano
