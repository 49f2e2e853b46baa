#include "bake/mesh/rbc_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>

#include "bake/mesh/vertex_normals.hpp"
#include "common/error.hpp"

namespace nano::mesh {

double EvansFungShape::half_thickness(double r) const {
  const double rho2 = std::min(1.0, (r / r0) * (r / r0));
  return 0.5 * r0 * std::sqrt(1.0 - rho2) * (c0 + c1 * rho2 + c2 * rho2 * rho2);
}

namespace {

constexpr double pi = std::numbers::pi;
constexpr double curvature_length = 0.5 * angstrom_per_micrometre;  // ℓc
constexpr double disk_radius = 0.24;

// Meridian point (r, z) at parameter θ ∈ [0, π].
glm::dvec2 meridian(const EvansFungShape& shape, double theta) {
  const double s2 = std::sin(theta) * std::sin(theta);
  return {shape.r0 * std::sin(theta), 0.5 * shape.r0 * std::cos(theta) * (shape.c0 + shape.c1 * s2 + shape.c2 * s2 * s2)};
}

// Dense tables over the upper half θ ∈ [0, π/2]: arc length and curvature-weighted arc length.
struct MeridianTable {
  std::vector<double> theta, arc, weighted;
};

MeridianTable tabulate(const EvansFungShape& shape) {
  constexpr int steps = 20000;
  MeridianTable table;
  const double d = 0.5 * pi / steps;
  double arc = 0.0, weighted = 0.0;
  for (int i = 0; i <= steps; ++i) {
    const double theta = i * d;
    if (i > 0) {
      const double mid = theta - 0.5 * d;
      // Curvature of the plane curve from central differences (h small against the shape).
      const double h = 1e-4;
      const glm::dvec2 p0 = meridian(shape, mid - h), p1 = meridian(shape, mid), p2 = meridian(shape, mid + h);
      const glm::dvec2 d1 = (p2 - p0) / (2 * h), d2 = (p2 - 2.0 * p1 + p0) / (h * h);
      const double speed = glm::length(d1);
      const double curvature = std::abs(d1.x * d2.y - d1.y * d2.x) / (speed * speed * speed);
      const double ds = glm::length(meridian(shape, theta) - meridian(shape, theta - d));
      arc += ds;
      weighted += ds * (1.0 + curvature_length * curvature);
    }
    table.theta.push_back(theta);
    table.arc.push_back(arc);
    table.weighted.push_back(weighted);
  }
  return table;
}

// Linear interpolation of column `to` at value x of the increasing column `from`.
double lookup(const std::vector<double>& from, const std::vector<double>& to, double x) {
  const auto it = std::lower_bound(from.begin(), from.end(), x);
  if (it == from.begin()) return to.front();
  if (it == from.end()) return to.back();
  const std::size_t i = static_cast<std::size_t>(it - from.begin());
  const double t = (x - from[i - 1]) / (from[i] - from[i - 1]);
  return to[i - 1] + t * (to[i] - to[i - 1]);
}

struct Ring {
  double theta = 0.0;
  double arc_from_pole = 0.0;  // measured from the pole of its own half
  int count = 1;               // 1 for a pole
  double offset = 0.0;         // azimuth of vertex 0, in units of the ring's segment
  std::uint32_t first_position = 0;
};

// Connects ring a to ring b (b one step further along θ) with count(a) + count(b) triangles,
// merging the two azimuth sequences; (a_i, b_j, ·) winds outward for increasing θ (see header).
void stitch(const Ring& a, const Ring& b, std::vector<Triangle>& out) {
  const int na = a.count > 1 ? a.count : 0, nb = b.count > 1 ? b.count : 0;
  auto azimuth = [](const Ring& r, int k) { return (k + r.offset) / r.count; };
  auto vertex = [](const Ring& r, int k) { return r.first_position + static_cast<std::uint32_t>(r.count > 1 ? k % r.count : 0); };
  int i = 0, j = 0;
  while (i < na || j < nb) {
    const bool advance_a = j == nb || (i < na && azimuth(a, i + 1) <= azimuth(b, j + 1));
    if (advance_a) {
      out.push_back({vertex(a, i), vertex(b, j), vertex(a, i + 1)});
      ++i;
    } else {
      out.push_back({vertex(a, i), vertex(b, j), vertex(b, j + 1)});
      ++j;
    }
  }
}

ProxyMesh build(const EvansFungShape& shape, const MeridianTable& table, double edge) {
  // Upper half rings 0..m (0 = pole, m = rim), mirrored for the lower half.
  const int m = std::max(2, static_cast<int>(std::lround(table.weighted.back() / edge)));
  std::vector<Ring> rings(2 * m + 1);
  for (int k = 0; k <= m; ++k) {
    const double w = table.weighted.back() * k / m;
    rings[k].theta = k == m ? 0.5 * pi : lookup(table.weighted, table.theta, w);
    rings[k].arc_from_pole = k == m ? table.arc.back() : lookup(table.weighted, table.arc, w);
    rings[2 * m - k].theta = pi - rings[k].theta;
    rings[2 * m - k].arc_from_pole = rings[k].arc_from_pole;
  }
  ProxyMesh mesh;
  for (int k = 0; k <= 2 * m; ++k) {
    Ring& ring = rings[k];
    const int mirrored = std::min(k, 2 * m - k);
    if (mirrored > 0) {
      // Meridional spacing around this ring; near-equilateral triangles have a base of 2/√3 of it.
      // Across the rim the next ring is the mirror of the previous one, at the same distance.
      const double before = rings[mirrored - 1].arc_from_pole;
      const double after = mirrored < m ? rings[mirrored + 1].arc_from_pole : 2.0 * rings[m].arc_from_pole - before;
      const double spacing = 0.5 * (after - before);
      const double radius = meridian(shape, ring.theta).x;
      ring.count = std::max(3, static_cast<int>(std::lround(2.0 * pi * radius * std::sqrt(3.0) / (2.0 * spacing))));
      ring.offset = 0.5 * (mirrored % 2);
    }
    ring.first_position = static_cast<std::uint32_t>(mesh.positions.size());
    glm::dvec2 rz = meridian(shape, ring.theta);
    if (ring.count == 1) rz.x = 0.0;  // sin(π) is 1e-16, not 0: put the bottom pole on the axis
    for (int i = 0; i < ring.count; ++i) {
      const double phi = 2.0 * pi * (i + ring.offset) / ring.count;
      mesh.positions.push_back({rz.x * std::cos(phi), rz.x * std::sin(phi), rz.y});
    }
  }
  for (int k = 0; k < 2 * m; ++k) stitch(rings[k], rings[k + 1], mesh.triangles);

  // UVs: one set for the upper half (rings 0..m), one for the lower (m..2m); only the rim has both.
  auto uv_of = [&](int k, int i, bool lower) {
    const Ring& ring = rings[k];
    const double phi = 2.0 * pi * (i + ring.offset) / ring.count;
    const double rho = disk_radius * ring.arc_from_pole / table.arc.back();
    return lower ? glm::dvec2(0.75 + rho * std::cos(phi), 0.5 - rho * std::sin(phi))
                 : glm::dvec2(0.25 + rho * std::cos(phi), 0.5 + rho * std::sin(phi));
  };
  std::vector<std::uint32_t> upper_uv(mesh.positions.size()), lower_uv(mesh.positions.size());
  for (int k = 0; k <= 2 * m; ++k) {
    for (int i = 0; i < rings[k].count; ++i) {
      const std::uint32_t p = rings[k].first_position + static_cast<std::uint32_t>(i);
      if (k <= m) {
        upper_uv[p] = static_cast<std::uint32_t>(mesh.uvs.size());
        mesh.uvs.push_back(uv_of(k, i, false));
      }
      if (k >= m) {
        lower_uv[p] = static_cast<std::uint32_t>(mesh.uvs.size());
        mesh.uvs.push_back(uv_of(k, i, true));
      }
    }
  }
  const std::uint32_t first_below_rim = rings[m + 1].first_position;
  for (const Triangle& t : mesh.triangles) {
    // A triangle is in the lower half when any corner lies below the rim ring.
    const bool lower = std::any_of(t.begin(), t.end(), [&](std::uint32_t p) { return p >= first_below_rim; });
    Triangle uv{};
    for (int c = 0; c < 3; ++c) uv[c] = lower ? lower_uv[t[c]] : upper_uv[t[c]];
    mesh.uv_triangles.push_back(uv);
  }
  compute_angle_weighted_normals(mesh);
  return mesh;
}

}  // namespace

ProxyMesh make_rbc_mesh(int target_triangles, const EvansFungShape& shape) {
  if (target_triangles < 200)
    throw InputError("", "--triangles", "the red blood cell needs at least 200 triangles, got " + std::to_string(target_triangles));
  const MeridianTable table = tabulate(shape);
  // Start from the flat-disk estimate (area ≈ 2πR0², equilateral triangles), then correct the
  // edge length by the square root of the count ratio until within 5% of the target.
  double edge = std::sqrt(4.0 * 2.0 * pi * shape.r0 * shape.r0 / (std::sqrt(3.0) * target_triangles));
  ProxyMesh mesh = build(shape, table, edge);
  for (int iteration = 0; iteration < 8; ++iteration) {
    const double ratio = static_cast<double>(mesh.triangles.size()) / target_triangles;
    if (std::abs(ratio - 1.0) < 0.05) break;
    edge *= std::sqrt(ratio);
    mesh = build(shape, table, edge);
  }
  return mesh;
}

}  // namespace nano::mesh
