#pragma once
// Exact-in-double closest point on a triangle (Ericson, Real-Time Collision Detection §5.1.5):
// the Voronoi region of the query point decides between a vertex, an edge and the face.
#include <glm/vec3.hpp>

namespace nano::grid {

glm::dvec3 closest_point_on_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);
double squared_distance_to_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

}  // namespace nano::grid
