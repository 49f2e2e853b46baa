#pragma once
// Independent oracles for the core-grid tests: none of them calls the code under test or CGAL.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "bake/mesh/proxy_mesh.hpp"
#include "bake/mesh/rbc_mesh.hpp"

namespace nano::grid::oracle {

inline double segment_distance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

// Not Ericson's Voronoi regions: project onto the plane, test barycentric signs, else the
// nearest of the three edges.
inline double triangle_distance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double n2 = glm::dot(n, n);
  if (n2 > 0.0) {
    const glm::dvec3 q = p - (glm::dot(p - a, n) / n2) * n;
    const double u = glm::dot(glm::cross(b - q, c - q), n), v = glm::dot(glm::cross(c - q, a - q), n),
                 w = glm::dot(glm::cross(a - q, b - q), n);
    if (u >= 0.0 && v >= 0.0 && w >= 0.0) return std::abs(glm::dot(p - a, n)) / std::sqrt(n2);
  }
  return std::min({segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
}

inline double mesh_distance(const mesh::ProxyMesh& m, const glm::dvec3& p) {
  double d = std::numeric_limits<double>::infinity();
  for (const mesh::Triangle& t : m.triangles)
    d = std::min(d, triangle_distance(p, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
  return d;
}

// Generalised winding number (van Oosterom & Strackee solid angles): ≈ 1 inside, ≈ 0 outside.
inline bool mesh_contains(const mesh::ProxyMesh& m, const glm::dvec3& p) {
  double total = 0.0;
  for (const mesh::Triangle& t : m.triangles) {
    const glm::dvec3 a = m.positions[t[0]] - p, b = m.positions[t[1]] - p, c = m.positions[t[2]] - p;
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double num = glm::dot(a, glm::cross(b, c));
    const double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(b, c) * la + glm::dot(c, a) * lb;
    total += 2.0 * std::atan2(num, den);
  }
  return std::abs(total / (4.0 * std::numbers::pi)) > 0.5;
}

// The Evans–Fung implicit function of shared/data/BIOLOGY.md §1.2: negative inside.
inline double evans_fung(const glm::dvec3& p, const mesh::EvansFungShape& s = {}) {
  const double q = (p.x * p.x + p.y * p.y) / (s.r0 * s.r0);
  const double poly = s.c0 + s.c1 * q + s.c2 * q * q;
  return 4.0 * p.z * p.z / (s.r0 * s.r0) - (1.0 - q) * poly * poly;
}

// Distance to the analytic Evans–Fung surface: a surface of revolution, so the distance in the
// (r, |z|) half-plane to a finely sampled upper meridian (chord error < 0.5 Å at 1000 segments).
class EvansFungDistance {
public:
  explicit EvansFungDistance(const mesh::EvansFungShape& s = {}, int segments = 1000) {
    for (int i = 0; i <= segments; ++i) {
      const double theta = 0.5 * std::numbers::pi * i / segments, sn = std::sin(theta);
      meridian_.push_back({s.r0 * sn, 0.5 * s.r0 * std::cos(theta) * (s.c0 + s.c1 * sn * sn + s.c2 * sn * sn * sn * sn), 0.0});
    }
  }
  double operator()(const glm::dvec3& p) const {
    const glm::dvec3 q(std::hypot(p.x, p.y), std::abs(p.z), 0.0);
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i + 1 < meridian_.size(); ++i) d = std::min(d, segment_distance(q, meridian_[i], meridian_[i + 1]));
    return d;
  }

private:
  std::vector<glm::dvec3> meridian_;
};

// Corners, face centres, edge midpoints and centre of a box: the 3×3×3 lattice.
inline std::vector<glm::dvec3> box_samples(const glm::dvec3& lo, double size) {
  std::vector<glm::dvec3> s;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) s.push_back(lo + 0.5 * size * glm::dvec3(i, j, k));
  return s;
}

inline double box_min_radius(const glm::dvec3& lo, double size) {
  const glm::dvec3 hi = lo + size;
  return glm::length(glm::clamp(glm::dvec3(0.0), lo, hi));
}
inline double box_max_radius(const glm::dvec3& lo, double size) {
  const glm::dvec3 hi = lo + size;
  return glm::length(glm::max(glm::abs(lo), glm::abs(hi)));
}

}  // namespace nano::grid::oracle
