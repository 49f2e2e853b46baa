// libFuzzer target: arbitrary bytes through the strict JSON reader and the cellPACK recipe reader
// (v1 and v2; v1 includes are looked for beside a recipe path that does not exist, so each is a
// named refusal), and through the .sph sphere tree reader. Rejection as an InputError is the expected outcome; anything else (another
// exception, a crash, a sanitizer report, a hang, an accepted recipe holding a value the reader
// promises never to pass on) is a finding. fuzz_recipe is nano_fuzzer's reader "recipe"
// (fuzz_main.cpp).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <string>
#include <string_view>

#include "bake/cellpack/recipe_reader.hpp"
#include "bake/cellpack/sphere_tree.hpp"
#include "common/error.hpp"
#include "common/json_document.hpp"

namespace {

using namespace nano;
using namespace nano::cellpack;

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "recipe fuzzer: %s\n", what.c_str());
  std::abort();
}

void check_finite(const glm::dvec3& v, const char* what) {
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) finding(std::string("accepted recipe holds a non-finite ") + what);
}

void check_ingredient(const Ingredient& in) {
  if (!(in.molarity >= 0.0) || !std::isfinite(in.molarity)) finding("accepted recipe holds a molarity < 0 or non-finite");
  if (double(in.count) > kMaxIngredientCount) finding("accepted recipe holds a count over 10^12");
  if (in.principal_vector) check_finite(*in.principal_vector, "principal vector");
  if (in.offset) check_finite(*in.offset, "offset");
  if (in.colour) {
    check_finite(*in.colour, "colour");
    for (int k = 0; k < 3; ++k)
      if ((*in.colour)[k] < 0.0 || (*in.colour)[k] > 1.0) finding("accepted recipe holds a colour outside 0–1");
  }
  if (!(in.encapsulating_radius >= 0.0) || !std::isfinite(in.encapsulating_radius)) finding("accepted recipe holds a bad radius");
  for (const glm::dvec4& s : in.spheres) {
    check_finite(glm::dvec3(s), "sphere centre");
    if (!(s.w > 0.0) || !std::isfinite(s.w)) finding("accepted recipe holds a sphere radius <= 0");
  }
}

void run(std::string_view text) {
  const Recipe r = parse_recipe(parse_json_text(text, "fuzz.json"), "fuzz/recipe.json");
  for (const Ingredient& in : r.outside) check_ingredient(in);
  for (const Compartment& c : r.compartments) {
    if (c.geometry == Compartment::Geometry::sphere && !(c.radius > 0.0 && std::isfinite(c.radius)))
      finding("accepted recipe holds a sphere compartment without a radius > 0");
    check_finite(c.centre, "compartment centre");
    for (const Ingredient& in : c.surface) check_ingredient(in);
    for (const Ingredient& in : c.interior) check_ingredient(in);
  }
}

void run_sphere_tree(std::string_view text) {
  const SphereTree t = parse_sphere_tree(text, "fuzz.sph");
  std::size_t total = 0;
  for (const auto& level : t.levels)
    for (const glm::dvec4& s : level) {
      check_finite(glm::dvec3(s), "sphere centre");
      if (!(s.w > 0.0) || !std::isfinite(s.w)) finding("accepted sphere tree holds a radius <= 0");
      ++total;
    }
  if (total > kMaxSphereTreeSpheres) finding("accepted sphere tree holds too many spheres");
}

}  // namespace

namespace nano::fuzz {

void fuzz_recipe(std::span<const std::byte> bytes) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  try {
    run(text);
  } catch (const InputError&) {
  }
  try {
    run_sphere_tree(text);
  } catch (const InputError&) {
  }
}

}  // namespace nano::fuzz
