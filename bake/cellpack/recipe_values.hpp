#pragma once
// The values of cellPACK recipes as the two formats write them, read leniently where cellPACK's own
// files are loose (numbers as strings, colours in 0–255, "None" for nothing) and strictly where a
// value reaches the scene (a negative molarity, a fractional or absurd count, a NaN vector).
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/json_cursor.hpp"

namespace nano::cellpack {

// A number, or a string holding one (Mesoscope exports write radii as "20").
double lenient_number(const JsonCursor& c);
// mol/L, finite and ≥ 0; absent or null: 0.
double read_molarity(const std::optional<JsonCursor>& c);
// A whole number of copies in [0, kMaxIngredientCount]; absent or null: 0.
std::uint64_t read_count(const std::optional<JsonCursor>& c);
// Three finite numbers; absent or null: nothing.
std::optional<glm::dvec3> read_optional_vec3(const std::optional<JsonCursor>& c);
// A colour in 0–1, or in 0–255 when any component is above 1 (scaled down); absent or null: nothing.
std::optional<glm::dvec3> read_colour(const std::optional<JsonCursor>& c);
// A string that means something: absent, null, "", "None" and "none" are nothing.
std::string read_name(const std::optional<JsonCursor>& c);
// v1 inline sphere tree: `radii` [[r…]…] and `positions` [[[x,y,z]…]…] by level, or the Mesoscope
// form [{"radii": […]}] and [{"coords": [x0,y0,z0,x1,…]}]; the finest level that has both.
std::vector<glm::dvec4> read_inline_spheres(const std::optional<JsonCursor>& radii, const std::optional<JsonCursor>& positions);

}  // namespace nano::cellpack
