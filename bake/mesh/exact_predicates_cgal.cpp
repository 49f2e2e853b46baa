// CGAL's filtered exact predicates (Epick), alone in a translation unit of the readers' library.
#include "bake/mesh/exact_predicates.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace nano::mesh {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
}  // namespace

bool exactly_collinear(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  using Point3 = Kernel::Point_3;
  return CGAL::collinear(Point3(a.x, a.y, a.z), Point3(b.x, b.y, b.z), Point3(c.x, c.y, c.z));
}

int exact_orientation_2d(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  using Point2 = Kernel::Point_2;
  return static_cast<int>(CGAL::orientation(Point2(a.x, a.y), Point2(b.x, b.y), Point2(c.x, c.y)));
}

}  // namespace nano::mesh
