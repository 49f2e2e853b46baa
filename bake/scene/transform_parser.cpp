#include "bake/scene/transform_parser.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace nano::scene {

glm::dvec3 rescaled_by_power_of_two(const glm::dvec3& v) {
  const int e = std::ilogb(std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}));
  return {std::ldexp(v.x, -e), std::ldexp(v.y, -e), std::ldexp(v.z, -e)};
}

namespace {

Matrix3x4 parse_translate_rotate_scale(const JsonCursor& c) {
  c.only_keys({"translate", "rotate", "scale"});
  const glm::dvec3 translate = c.has("translate") ? c.required("translate").vec3() : glm::dvec3(0.0);
  glm::dvec3 axis(0.0, 0.0, 1.0);
  double degrees = 0.0;
  if (const auto rotate = c.optional("rotate")) {
    rotate->only_keys({"axis", "degrees"});
    axis = rescaled_by_power_of_two(rotate->required("axis").non_zero_vec3());
    degrees = rotate->required("degrees").number();
  }
  const double scale = c.has("scale") ? c.required("scale").number_greater_than(0.0) : 1.0;
  return translate_rotate_scale(translate, axis, degrees, scale);
}

Matrix3x4 parse_matrix(const JsonCursor& c) {
  const auto rows = c.elements();
  if (rows.size() != 3) c.fail("expected 3 rows of 4 numbers (3x4 row-major), got " + c.shown());
  const Matrix3x4 m = {rows[0].vec4(), rows[1].vec4(), rows[2].vec4()};
  const double det = linear_determinant(m);
  if (!(det > 0.0)) {
    std::ostringstream s;
    s << "the left 3x3 part must have a positive determinant (no mirroring, not flat), got " << det;
    c.fail(s.str());
  }
  return m;
}

}  // namespace

Matrix3x4 parse_placement_transform(const JsonCursor& owner) {
  const auto trs = owner.optional("transform");
  const auto matrix = owner.optional("matrix");
  if (trs && matrix) owner.fail("give either \"transform\" or \"matrix\", not both");
  if (trs) return parse_translate_rotate_scale(*trs);
  if (matrix) return parse_matrix(*matrix);
  return identity_transform();
}

}  // namespace nano::scene
