#include "bake/cellpack/recipe_values.hpp"

#include <cmath>
#include <cstdlib>

#include "bake/cellpack/recipe_reader.hpp"

namespace nano::cellpack {
namespace {

bool absent(const std::optional<JsonCursor>& c) { return !c || c->json().is_null(); }

// Per level: the radii and the centres, both as flat lists of numbers.
std::vector<JsonCursor> level_list(const JsonCursor& level, const char* mesoscope_key) {
  if (level.json().is_object()) return level.required(mesoscope_key).elements();
  return level.elements();
}

}  // namespace

double lenient_number(const JsonCursor& c) {
  if (c.json().is_string()) {
    const std::string s = c.string();
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v)) c.fail("expected a number, got " + c.shown());
    return v;
  }
  const double v = c.number();
  if (!std::isfinite(v)) c.fail("expected a finite number, got " + c.shown());
  return v;
}

double read_molarity(const std::optional<JsonCursor>& c) {
  if (absent(c)) return 0.0;
  const double m = lenient_number(*c);
  if (!(m >= 0.0)) c->fail("a molarity is a concentration in mol/L, >= 0; got " + c->shown());
  return m;
}

std::uint64_t read_count(const std::optional<JsonCursor>& c) {
  if (absent(c)) return 0;
  const double n = lenient_number(*c);
  if (!(n >= 0.0) || n != std::floor(n))
    c->fail("expected a whole number of copies >= 0, got " + c->shown());
  if (n > kMaxIngredientCount)
    c->fail("at most 10^12 copies of one ingredient (a whole red blood cell holds 2.8·10^8 haemoglobins), got " + c->shown());
  return std::uint64_t(n);
}

std::optional<glm::dvec3> read_optional_vec3(const std::optional<JsonCursor>& c) {
  if (absent(c)) return std::nullopt;
  const std::vector<JsonCursor> e = c->elements();
  if (e.size() != 3) c->fail("expected [x, y, z], got " + c->shown());
  return glm::dvec3(lenient_number(e[0]), lenient_number(e[1]), lenient_number(e[2]));
}

std::optional<glm::dvec3> read_colour(const std::optional<JsonCursor>& c) {
  std::optional<glm::dvec3> rgb = read_optional_vec3(c);
  if (!rgb) return rgb;
  if (rgb->x < 0 || rgb->y < 0 || rgb->z < 0 || rgb->x > 255 || rgb->y > 255 || rgb->z > 255)
    c->fail("expected a colour with components in 0–1 (or 0–255), got " + c->shown());
  if (rgb->x > 1 || rgb->y > 1 || rgb->z > 1) *rgb /= 255.0;
  return rgb;
}

std::string read_name(const std::optional<JsonCursor>& c) {
  if (absent(c)) return "";
  const std::string s = c->string();
  return s == "None" || s == "none" ? "" : s;
}

std::vector<glm::dvec4> read_inline_spheres(const std::optional<JsonCursor>& radii, const std::optional<JsonCursor>& positions) {
  if (absent(radii) || absent(positions)) return {};
  const std::vector<JsonCursor> r_levels = radii->elements(), p_levels = positions->elements();
  for (std::size_t level = std::min(r_levels.size(), p_levels.size()); level-- > 0;) {
    const std::vector<JsonCursor> r = level_list(r_levels[level], "radii");
    const std::vector<JsonCursor> p = level_list(p_levels[level], "coords");
    // Nested [[x,y,z],…] or the Mesoscope flat [x0,y0,z0,x1,…].
    const bool flat = !p.empty() && !p[0].json().is_array();
    if (r.empty()) continue;
    if ((flat ? p.size() / 3 : p.size()) != r.size() || (flat && p.size() % 3 != 0))
      p_levels[level].fail("expected one centre per radius (" + std::to_string(r.size()) + " radii), got " + p_levels[level].shown());
    std::vector<glm::dvec4> spheres;
    for (std::size_t k = 0; k < r.size(); ++k) {
      const double rad = lenient_number(r[k]);
      if (!(rad > 0.0)) r[k].fail("expected a sphere radius > 0 Å, got " + r[k].shown());
      if (!flat && p[k].json().is_null()) p[k].fail("expected a sphere centre [x, y, z], got null");
      const glm::dvec3 centre = flat ? glm::dvec3(lenient_number(p[3 * k]), lenient_number(p[3 * k + 1]), lenient_number(p[3 * k + 2]))
                                     : *read_optional_vec3(p[k]);
      spheres.emplace_back(centre, rad);
    }
    return spheres;
  }
  return {};
}

}  // namespace nano::cellpack
