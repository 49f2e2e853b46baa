#pragma once
// Fixtures and independent double-precision oracles of the shell tests. The oracles share no code
// with bake/shell or the shared headers: their own barycentrics, ray/triangle and ray/bilinear-patch
// intersection (two planes through the ray, a quadratic in u — not Reshetov's formulation).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bake/mesh/rbc_mesh.hpp"
#include "bake/mesh/sphere_mesh.hpp"
#include "bake/mesh/uv_distortion.hpp"
#include "bake/shell/membrane_mapping.hpp"
#include "bake/shell/shell_offsets.hpp"
#include "bake/tiles/tiling_recipe.hpp"
#include "bake/tiles/wang_sets.hpp"

namespace shell_test {

using glm::dvec2;
using glm::dvec3;

// Small synthetic molecules so a real-size (200 Å) tile set generates in well under a second.
// Lipid: a 4-atom stick along z; protein: 24 atoms in an ellipsoid whose centre sits 8 Å above the
// molecule origin (so the radius about the origin differs from the one about the centroid).
inline nano::tiles::MoleculeType make_stick_lipid() {
  nano::tiles::MoleculeType m{"stick", {}, 0.f, {0.f, 0.f, 1.f}};
  for (int i = 0; i < 4; ++i) m.atoms.push_back({{i == 0 ? 1.0f : 0.f, 0.f, -7.f + 4.5f * i}, 1.7f});
  return m;
}

inline nano::tiles::MoleculeType make_offset_protein() {
  nano::tiles::MoleculeType m{"protein", {}, 0.f, {0.f, 0.f, 1.f}};
  std::uint64_t s = 7;
  auto next = [&] {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return double(s >> 11) * 0x1.0p-53 * 2.0 - 1.0;
  };
  while (m.atoms.size() < 24) {
    const double x = next(), y = next(), z = next();
    if (x * x + y * y + z * z > 1.0) continue;
    m.atoms.push_back({{float(12 * x), float(9 * y), float(8.0 + 16 * z)}, 1.7f});
  }
  return m;
}

// Bounding radius about the origin from the atoms (double, rounded up to float), as the package's
// MoleculeType.aabb_min.w holds it: the seam rule's radius.
inline nano::tiles::MoleculeType with_radius(nano::tiles::MoleculeType m) {
  double r = 0.0;
  for (const auto& a : m.atoms) r = std::max(r, glm::length(glm::dvec3(a.centre)) + double(a.radius));
  float f = float(r);
  if (double(f) < r) f = std::nextafter(f, INFINITY);
  m.bounding_radius = f;
  return m;
}

struct Scene {
  nano::mesh::ProxyMesh mesh;
  std::vector<nano::tiles::MoleculeType> types;
  nano::tiles::WangSet set;
  nano::tiles::TilingRecipe recipe;
  double k = 0.0;
  std::unique_ptr<nano::shell::MembraneMapping> mapping;
};

// Membrane: stick lipids at 400 Å² per lipid per leaflet (±16 Å), one protein per tile at depth 22 Å.
inline nano::tiles::WangSet make_test_set(const std::vector<nano::tiles::MoleculeType>& types) {
  nano::tiles::MembraneTileRequest r;
  r.types = types;
  r.edge = 200.f;
  r.colours = 2;
  r.molecules = {{1, 1.0 / (200.0 * 200.0 * 1e-8), 22.f}};
  r.lipids = nano::tiles::LipidFill{0, 400.f, 16.f};
  r.seed = 5;
  return nano::tiles::make_membrane_tiles(r);
}

inline std::unique_ptr<Scene> make_scene(nano::mesh::ProxyMesh mesh) {
  auto sc = std::make_unique<Scene>();
  sc->mesh = std::move(mesh);
  sc->types = {with_radius(make_stick_lipid()), with_radius(make_offset_protein())};
  sc->set = make_test_set(sc->types);
  sc->k = nano::mesh::uv_scale(sc->mesh);
  // Deliberately much smaller than the UV range (3×2 cells), so the wrap of tile_at is exercised.
  sc->recipe = nano::tiles::make_tiling_recipe(sc->set.colouring, {3, 2, 1}, 9, true);
  sc->mapping = std::make_unique<nano::shell::MembraneMapping>(sc->mesh, sc->set, sc->recipe, sc->k, sc->types);
  return sc;
}

// Virion-sized sphere (radius 500 Å) and a small RBC (R0 = 2000 Å) at a modest triangle count.
inline std::unique_ptr<Scene> sphere_scene() { return make_scene(nano::mesh::make_sphere_mesh(300, 500.0)); }
inline std::unique_ptr<Scene> rbc_scene() {
  nano::mesh::EvansFungShape shape;
  shape.r0 = 2000.0;
  return make_scene(nano::mesh::make_rbc_mesh(300, shape));
}

// ---- independent oracles (double) ----

// Barycentrics of p in UV triangle (a, b, c); nullopt if degenerate.
inline std::optional<dvec3> barycentric(dvec2 a, dvec2 b, dvec2 c, dvec2 p) {
  const double det = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (det == 0.0) return std::nullopt;
  const double l1 = ((p.x - a.x) * (c.y - a.y) - (p.y - a.y) * (c.x - a.x)) / det;
  const double l2 = ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)) / det;
  return dvec3(1.0 - l1 - l2, l1, l2);
}

inline double point_segment_distance(dvec2 p, dvec2 a, dvec2 b) {
  const dvec2 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0.0 ? glm::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

// Line o + t·d vs triangle (a, b, c), closed; appends t.
inline void line_triangle(dvec3 o, dvec3 d, dvec3 a, dvec3 b, dvec3 c, std::vector<double>& ts) {
  const dvec3 e1 = b - a, e2 = c - a;
  const dvec3 n = glm::cross(e1, e2);
  const double dn = glm::dot(d, n);
  if (dn == 0.0) return;
  const double t = glm::dot(a - o, n) / dn;
  const dvec3 p = o + t * d;
  const double area = glm::dot(n, n);
  const double u = glm::dot(glm::cross(p - a, e2), n) / area;  // weight of b
  const double v = glm::dot(glm::cross(e1, p - a), n) / area;  // weight of c
  if (u >= 0.0 && v >= 0.0 && u + v <= 1.0) ts.push_back(t);
}

// Line o + t·d vs bilinear patch X(u,v) = p00 + u·e + v·f + uv·g, (u, v) ∈ [0,1]²; appends t.
// Two planes containing the line (normals a, b ⟂ d) give A + B u + C v + D uv = 0 each; eliminating v
// leaves a quadratic in u.
inline void line_patch(dvec3 o, dvec3 d, dvec3 p00, dvec3 p10, dvec3 p01, dvec3 p11, std::vector<double>& ts) {
  const dvec3 e = p10 - p00, f = p01 - p00, g = p11 - p10 - p01 + p00;
  const dvec3 dn = glm::normalize(d);
  const dvec3 helper = std::abs(dn.x) < 0.6 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
  const dvec3 a = glm::normalize(glm::cross(dn, helper));
  const dvec3 b = glm::cross(dn, a);
  const double A1 = glm::dot(a, p00 - o), B1 = glm::dot(a, e), C1 = glm::dot(a, f), D1 = glm::dot(a, g);
  const double A2 = glm::dot(b, p00 - o), B2 = glm::dot(b, e), C2 = glm::dot(b, f), D2 = glm::dot(b, g);
  const double qa = B2 * D1 - D2 * B1;
  const double qb = A2 * D1 + B2 * C1 - C2 * B1 - D2 * A1;
  const double qc = A2 * C1 - C2 * A1;
  double roots[2];
  int n = 0;
  const double scale = std::abs(qb) + std::abs(qc) + 1e-300;
  if (std::abs(qa) <= 1e-14 * scale) {
    if (qb != 0.0) roots[n++] = -qc / qb;
  } else {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc < 0.0) return;
    const double sq = std::sqrt(disc);
    roots[n++] = (-qb + sq) / (2.0 * qa);
    roots[n++] = (-qb - sq) / (2.0 * qa);
  }
  for (int i = 0; i < n; ++i) {
    const double u = roots[i];
    if (!(u >= 0.0 && u <= 1.0)) continue;
    const double den1 = C1 + D1 * u, den2 = C2 + D2 * u;
    const double v = std::abs(den1) >= std::abs(den2) ? -(A1 + B1 * u) / den1 : -(A2 + B2 * u) / den2;
    if (!(v >= 0.0 && v <= 1.0)) continue;
    const dvec3 x = p00 + u * e + v * f + u * v * g;
    ts.push_back(glm::dot(x - o, d) / glm::dot(d, d));
  }
}

// The 14 fixed directions: ±axes and the 8 cube diagonals (unit).
inline std::vector<dvec3> fourteen_directions() {
  std::vector<dvec3> dirs;
  for (int a = 0; a < 3; ++a)
    for (int s = -1; s <= 1; s += 2) {
      dvec3 d(0.0);
      d[a] = s;
      dirs.push_back(d);
    }
  for (int i = 0; i < 8; ++i)
    dirs.push_back(glm::normalize(dvec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1)));
  return dirs;
}

// True if the sphere (c, r) passes the ray oracle for the prism with vertices v (order of
// ray_prism.h): along each of the 14 directions an odd number of boundary crossings lies ahead
// (centre inside) and the nearest is at distance ≥ r.
inline bool sphere_in_prism_oracle(const dvec3 v[6], dvec3 c, double r) {
  static const std::vector<dvec3> dirs = fourteen_directions();
  std::vector<double> ts;
  for (const dvec3& d : dirs) {
    ts.clear();
    line_triangle(c, d, v[0], v[1], v[2], ts);
    line_triangle(c, d, v[3], v[4], v[5], ts);
    for (int w = 0; w < 3; ++w) {
      const int j = (w + 1) % 3;
      line_patch(c, d, v[w], v[j], v[w + 3], v[j + 3], ts);
    }
    int ahead = 0;
    double nearest = INFINITY;
    for (double t : ts)
      if (t > 0.0) {
        ahead += 1;
        nearest = std::min(nearest, t);
      }
    if (ahead % 2 == 0 || nearest < r) return false;
  }
  return true;
}

}  // namespace shell_test
