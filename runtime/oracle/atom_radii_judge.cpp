#include "runtime/oracle/atom_radii_judge.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/geometric.hpp>

#include "runtime/oracle/oracle_render.hpp"
#include "runtime/oracle/render_compare.hpp"

namespace nano::oracle {
namespace {

// Where the ray leaves the box (slab test); 0 when it never enters it ahead of the eye.
double exit_distance(const WorldBox& box, const glm::dvec3& eye, const glm::dvec3& direction) {
  double near = 0.0, far = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (direction[a] == 0.0) {
      if (eye[a] < box.min[a] || eye[a] > box.max[a]) return 0.0;
      continue;
    }
    double t0 = (box.min[a] - eye[a]) / direction[a], t1 = (box.max[a] - eye[a]) / direction[a];
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0);
    far = std::min(far, t1);
  }
  return far >= near ? far : 0.0;
}

}  // namespace

bool explained_as_tie(const ExplicitScene& scene, const glm::dvec3& eye, const glm::dvec3& direction,
                      const gpu::PixelHit& test, const gpu::PixelHit& reference, double largest_atom) {
  for (const gpu::PixelHit* hit : {&test, &reference})
    if (hit->atom == gpu::kNoHit || !(std::isfinite(hit->depth) && hit->depth > 0)) return false;
  const double tol = depth_tolerance(reference.depth);
  if (std::abs(double(test.depth) - double(reference.depth)) > tol) return false;
  const glm::dvec3 dir = glm::normalize(direction);
  const glm::dvec3 at = eye + double(reference.depth) * dir;
  const WorldBox box{at - (largest_atom + 2 * tol), at + (largest_atom + 2 * tol)};
  const auto number = [](const gpu::PixelHit& h) { return std::uint64_t{h.copy_number_hi} << 32 | h.copy_number_lo; };
  bool test_met = false, reference_met = false;
  scene.for_each_atom(box, [&](const AtomSample& s) {
    for (const gpu::PixelHit* hit : {&test, &reference}) {
      if (s.atom != hit->atom || s.copy->number != number(*hit)) continue;
      const double t = first_sphere_hit(eye, dir, s.position, s.radius);
      if (std::abs(t - double(hit->depth)) <= tol) (hit == &test ? test_met : reference_met) = true;
    }
  });
  return test_met && reference_met;
}

bool explained_by_placement(const ExplicitScene& scene, const glm::dvec3& eye, const glm::dvec3& direction,
                            const gpu::PixelHit& test, double slack, double largest_atom) {
  if (test.atom == gpu::kNoHit || !(std::isfinite(test.depth) && test.depth > 0)) return false;
  const glm::dvec3 dir = glm::normalize(direction);
  const double depth = test.depth, tol = depth_tolerance(depth);
  const glm::dvec3 at = eye + depth * dir;
  const WorldBox box{at - (largest_atom + 2 * slack + tol), at + (largest_atom + 2 * slack + tol)};
  const std::uint64_t number = std::uint64_t{test.copy_number_hi} << 32 | test.copy_number_lo;
  bool met = false;
  scene.for_each_atom(box, [&](const AtomSample& s) {
    if (met || s.atom != test.atom || s.copy->number != number) return;
    const glm::dvec3 oc = s.position - eye;
    const double tc = glm::dot(oc, dir);
    const double d = std::sqrt(std::max(0.0, glm::dot(oc, oc) - tc * tc));
    const double reach = s.radius + slack;
    if (glm::dot(oc, oc) <= reach * reach || d >= reach) return;  // the eye within reach, or no centre nearby meets the ray
    // The earliest entry: the ball of every shifted sphere; the latest: shifted away along the ray
    // and sideways, each by up to `slack` (tangent at worst).
    const double earliest = tc - std::sqrt(reach * reach - d * d);
    const double side = d + slack;
    const double latest = (side >= s.radius ? tc : tc - std::sqrt(s.radius * s.radius - side * side)) + slack;
    met = depth >= earliest - tol && depth <= latest + tol;
  });
  return met;
}

bool explained_by_atom_radii(const ExplicitScene& scene, const WorldBox& bounds, const glm::dvec3& eye,
                             const glm::dvec3& direction, const gpu::PixelHit& test, double epsilon,
                             double largest_atom, std::span<const glm::dvec4> clip, double medium_ulps) {
  const bool background = test.atom == gpu::kNoHit;
  if (!background && !(std::isfinite(test.depth) && test.depth > 0)) return false;
  const glm::dvec3 dir = glm::normalize(direction);
  const double reach = largest_atom * (1 + epsilon);
  const double depth = background ? INFINITY : double(test.depth);
  const double tol = background ? 0.0 : depth_tolerance(depth);
  const double end = background ? exit_distance(bounds, eye, dir) : depth + reach;
  if (!std::isfinite(end)) return false;

  const std::uint64_t test_copy = std::uint64_t{test.copy_number_hi} << 32 | test.copy_number_lo;
  bool found = false, blocked = false, eye_inside = false;
  constexpr double kChunk = 32.0;  // Å of ray per box query: keeps the boxes tight around the ray
  for (double t0 = 0.0; t0 < end && !blocked && !eye_inside; t0 += kChunk) {
    const glm::dvec3 a = eye + t0 * dir, b = eye + std::min(end, t0 + kChunk) * dir;
    // The medium's slack at the chunk's far end, the largest it reaches here.
    const float far = float(std::min(end, t0 + kChunk));
    const double box_reach = reach + medium_ulps * double(std::nextafter(far, INFINITY) - far);
    const WorldBox box{glm::min(a, b) - box_reach, glm::max(a, b) + box_reach};
    scene.for_each_atom(box, [&](const AtomSample& s) {
      for (const glm::dvec4& h : clip)  // clipped atoms are not there, whatever their radius
        if (!(glm::dot(glm::dvec3(h), s.position) + h.w >= 0)) return;
      const glm::dvec3 oc = s.position - eye;
      const double tc = glm::dot(oc, dir);
      const double d2 = std::max(0.0, glm::dot(oc, oc) - tc * tc);
      double slack = 0;
      if (medium_ulps > 0 && s.copy->id.kind == placement::CopyKind::medium) {
        const float distance = float(std::sqrt(glm::dot(oc, oc)));
        slack = medium_ulps * double(std::nextafter(distance, INFINITY) - distance);
      }
      const double grown = s.radius * (1 + epsilon) + slack, shrunk = std::max(0.0, s.radius * (1 - epsilon) - slack);
      if (d2 >= grown * grown) return;
      const double entry_grown = tc - std::sqrt(grown * grown - d2);
      if (tc + grown <= 0) return;  // wholly behind the eye
      if (entry_grown <= 0) {
        eye_inside = true;
        return;
      }
      const bool sure = d2 < shrunk * shrunk;  // hit whatever the radius
      const double entry_shrunk = sure ? tc - std::sqrt(shrunk * shrunk - d2) : tc;
      const bool is_test = !background && s.atom == test.atom && s.copy->number == test_copy;
      if (is_test) {
        found = found || (depth >= entry_grown - tol && depth <= entry_shrunk + tol);
      } else if (sure && entry_shrunk < depth - tol) {
        blocked = true;
      }
    });
  }
  return !eye_inside && !blocked && (background || found);
}

}  // namespace nano::oracle
