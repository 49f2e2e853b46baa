#pragma once
// Exact (filtered) predicates on double coordinates through CGAL: no tolerance, no false verdict.
// This header exposes no CGAL type; the one translation unit that includes CGAL for them,
// exact_predicates_cgal.cpp, is part of the readers' library (the polygon triangulation of
// polygon_soup.cpp decides with them), which keeps the rest of CGAL out of it.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace nano::mesh {

bool exactly_collinear(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);
int exact_orientation_2d(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c);  // +1 ccw, −1 cw, 0

}  // namespace nano::mesh
