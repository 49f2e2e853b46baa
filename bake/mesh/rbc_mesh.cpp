#include "bake/mesh/rbc_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <numeric>
#include <string>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "bake/mesh/uv_distortion.hpp"
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
// Bands grow while their own max σ1 / min σ2 stays within this; after every chart is scaled to the
// same smallest stretch it bounds the whole mesh's chart_anisotropy.
constexpr double band_anisotropy_tolerance = 1.03;
// A cone band r ≈ α·S + β unrolls to a sector of angle 2π·|α|; up to this |α| the two sides of its
// cut stay at least 5% of a turn apart, beyond it the band is split into sectors.
constexpr double max_sector_alpha = 0.95;
constexpr double layout_gutter = 0.02;  // around each chart, as a fraction of the layout's row width

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
  double meridian_arc = 0.0;   // S: along the polyline of rings from the top pole through the rim
  glm::dvec2 rz{0.0};          // meridian point: distance from the axis, height
  int count = 1;               // 1 for a pole
  double offset = 0.0;         // azimuth of vertex 0, in units of the ring's segment
  std::uint32_t first_position = 0;
};

// A triangle corner as stitch() walks it: its ring and its step along the ring. The walk's last
// triangles between two rings use step = count for vertex 0, so every triangle's corners have
// contiguous azimuths, and a band cut open there needs no further bookkeeping.
struct Corner {
  int ring = 0;
  int step = 0;
};

// The rings, the triangles between them and how each triangle was stitched.
struct RingMesh {
  ProxyMesh mesh;                                // positions and triangles; no UVs yet
  std::vector<Ring> rings;                       // 0 = top pole, rim, 2·rim = bottom pole
  int rim = 0;
  std::vector<std::array<Corner, 3>> corners;    // per triangle
  std::vector<std::size_t> first_triangle;       // triangles between ring k and k + 1 start here

  double azimuth(const Corner& c) const {
    const Ring& ring = rings[c.ring];
    return 2.0 * pi * (c.step + ring.offset) / ring.count;
  }
};

// Connects ring k to ring k + 1 with count(k) + count(k + 1) triangles, merging the two azimuth
// sequences; (a_i, b_j, ·) winds outward for increasing θ (see header).
void stitch(int k, RingMesh& out) {
  const Ring& a = out.rings[k];
  const Ring& b = out.rings[k + 1];
  const int na = a.count > 1 ? a.count : 0, nb = b.count > 1 ? b.count : 0;
  auto azimuth = [](const Ring& r, int step) { return (step + r.offset) / r.count; };
  auto emit = [&](const std::array<Corner, 3>& corners) {
    Triangle t{};
    for (int c = 0; c < 3; ++c) {
      const Ring& ring = out.rings[corners[c].ring];
      t[c] = ring.first_position + static_cast<std::uint32_t>(ring.count > 1 ? corners[c].step % ring.count : 0);
    }
    out.mesh.triangles.push_back(t);
    out.corners.push_back(corners);
  };
  int i = 0, j = 0;
  while (i < na || j < nb) {
    const bool advance_a = j == nb || (i < na && azimuth(a, i + 1) <= azimuth(b, j + 1));
    if (advance_a) {
      emit({Corner{k, i}, Corner{k + 1, j}, Corner{k, i + 1}});
      ++i;
    } else {
      emit({Corner{k, i}, Corner{k + 1, j}, Corner{k + 1, j + 1}});
      ++j;
    }
  }
}

RingMesh build(const EvansFungShape& shape, const MeridianTable& table, double edge) {
  // Upper half rings 0..m (0 = pole, m = rim), mirrored for the lower half.
  const int m = std::max(2, static_cast<int>(std::lround(table.weighted.back() / edge)));
  RingMesh out;
  out.rim = m;
  std::vector<Ring>& rings = out.rings;
  rings.resize(2 * m + 1);
  for (int k = 0; k <= m; ++k) {
    const double w = table.weighted.back() * k / m;
    rings[k].theta = k == m ? 0.5 * pi : lookup(table.weighted, table.theta, w);
    rings[k].arc_from_pole = k == m ? table.arc.back() : lookup(table.weighted, table.arc, w);
    rings[2 * m - k].theta = pi - rings[k].theta;
    rings[2 * m - k].arc_from_pole = rings[k].arc_from_pole;
  }
  ProxyMesh& mesh = out.mesh;
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
    ring.rz = meridian(shape, ring.theta);
    if (ring.count == 1) ring.rz.x = 0.0;  // sin(π) is 1e-16, not 0: put the bottom pole on the axis
    // The UV charts measure S along the chords between rings, as the triangles do, not along the
    // curved meridian: at the rim the two differ by ~1% at the default resolution.
    if (k > 0) ring.meridian_arc = rings[k - 1].meridian_arc + glm::distance(ring.rz, rings[k - 1].rz);
    for (int i = 0; i < ring.count; ++i) {
      const double phi = 2.0 * pi * (i + ring.offset) / ring.count;
      mesh.positions.push_back({ring.rz.x * std::cos(phi), ring.rz.x * std::sin(phi), ring.rz.y});
    }
  }
  for (int k = 0; k < 2 * m; ++k) {
    out.first_triangle.push_back(mesh.triangles.size());
    stitch(k, out);
  }
  out.first_triangle.push_back(mesh.triangles.size());
  return out;
}

// The triangles between rings first_ring and last_ring.
struct Band {
  int first_ring = 0, last_ring = 0;
};

// A band unrolled into the plane (UV in Å). With α ≠ 0 the band is taken for the cone
// r = α·S + β and unrolled about its apex: UV radius (α·S + β) / |α|, UV angle α·(φ − φ0). With
// α = 0 it is the cylinder r = β cut open: u = β·(φ − φ0), v = −S. Either way the meridional
// stretch is 1 and the circumferential one r / (α·S + β), and the winding is that of the top
// pole's (S, φ) disk, i.e. counter-clockwise seen from outside.
struct Development {
  double alpha = 0.0, beta = 0.0;
  double azimuth_origin = 0.0;  // φ0
  bool closed = false;          // all the way round a pole (α = ±1, β puts the apex on it): no cut

  glm::dvec2 uv(double s, double phi) const {
    const double turned = phi - azimuth_origin;
    if (alpha == 0.0) return {beta * turned, -s};
    const double rho = (alpha * s + beta) / std::abs(alpha);
    return rho * glm::dvec2(std::cos(alpha * turned), std::sin(alpha * turned));
  }
};

// Caps are azimuthal equidistant about their pole; a band through the rim is a cylinder and any
// other band the cone through its two boundary rings (the secant of r(S), the best line for a
// meridian that bends one way: the circumferential stretch is 1 on both boundaries).
Development develop(const RingMesh& rm, const Band& band) {
  const Ring& a = rm.rings[band.first_ring];
  const Ring& b = rm.rings[band.last_ring];
  if (a.count == 1) return {1.0, 0.0, 0.0, true};
  if (b.count == 1) return {-1.0, b.meridian_arc, 0.0, true};
  if (band.first_ring < rm.rim && rm.rim < band.last_ring) return {0.0, 0.5 * (a.rz.x + b.rz.x)};
  const double alpha = (b.rz.x - a.rz.x) / (b.meridian_arc - a.meridian_arc);
  return {alpha, a.rz.x - alpha * a.meridian_arc};
}

// A chart's key for a corner's UV: a closed chart makes vertex 0 and its wrap-around copy one.
Corner chart_corner(const RingMesh& rm, const Development& d, Corner c) {
  if (d.closed) c.step %= rm.rings[c.ring].count;
  return c;
}

glm::dvec2 developed_uv(const RingMesh& rm, const Development& d, const Corner& c) {
  const Corner key = chart_corner(rm, d, c);
  return d.uv(rm.rings[key.ring].meridian_arc, rm.azimuth(key));
}

// σ1, σ2 of the affine map from triangle t's corner UVs `uv` to its corner positions.
SingularValues stretch(const RingMesh& rm, std::size_t t, const std::array<glm::dvec2, 3>& uv) {
  const ProxyMesh& m = rm.mesh;
  return singular_values(*uv_jacobian({m.corner_position(t, 0), m.corner_position(t, 1), m.corner_position(t, 2)}, uv));
}

double band_anisotropy(const RingMesh& rm, const Band& band) {
  const Development d = develop(rm, band);
  double smallest = INFINITY, largest = 0.0;
  for (std::size_t t = rm.first_triangle[band.first_ring]; t < rm.first_triangle[band.last_ring]; ++t) {
    const auto& c = rm.corners[t];
    const SingularValues s = stretch(rm, t, {developed_uv(rm, d, c[0]), developed_uv(rm, d, c[1]), developed_uv(rm, d, c[2])});
    smallest = std::min(smallest, s.minor);
    largest = std::max(largest, s.major);
  }
  return largest / smallest;
}

// The largest k in (lo, hi] with fits(k), else lo. All are tried: a band's stretch is measured on
// its triangles, and a wider band can fit where a narrower one does not (its boundary rings, where
// the cone touches the surface, fall better on the meridian).
template <class Fits>
int widest(int lo, int hi, Fits fits) {
  for (int k = hi; k > lo; --k)
    if (fits(k)) return k;
  return lo;
}

// Bands from the top pole to the rim, each as wide as the tolerance allows for it and for its
// mirror image (the lower half is stitched in the other direction, so its triangles differ): first
// the cap from the pole, then a cylinder symmetric about the rim, then cones from the cap outward.
// A band is at least one ring gap even if that exceeds the tolerance; the cylinder needs two, and
// where those two exceed it (coarse meshes) the rim stays a seam between cones.
std::vector<Band> choose_bands(const RingMesh& rm) {
  const int m = rm.rim;
  auto mirror = [&](const Band& b) { return Band{2 * m - b.last_ring, 2 * m - b.first_ring}; };
  auto fits = [&](const Band& b) {
    return std::max(band_anisotropy(rm, b), band_anisotropy(rm, mirror(b))) <= band_anisotropy_tolerance;
  };
  const int cap_end = widest(1, m - 1, [&](int k) { return fits({0, k}); });
  const int rim_half = widest(0, m - cap_end, [&](int j) { return fits({m - j, m + j}); });
  std::vector<Band> top{{0, cap_end}};
  for (int first = cap_end; first < m - rim_half;) {
    const int last = widest(first + 1, m - rim_half, [&](int k) { return fits({first, k}); });
    top.push_back({first, last});
    first = last;
  }
  std::vector<Band> bands = top;
  if (rim_half > 0) bands.push_back({m - rim_half, m + rim_half});
  for (auto b = top.rbegin(); b != top.rend(); ++b) bands.push_back(mirror(*b));
  return bands;
}

struct Chart {
  Development development;
  std::vector<std::size_t> triangles;
};

// One chart per band, except that a cone band with |α| > max_sector_alpha is split by azimuth
// into sectors, each unrolled about its own middle.
std::vector<Chart> make_charts(const RingMesh& rm, const std::vector<Band>& bands) {
  std::vector<Chart> charts;
  for (const Band& band : bands) {
    const Development d = develop(rm, band);
    const std::size_t begin = rm.first_triangle[band.first_ring], end = rm.first_triangle[band.last_ring];
    double low = INFINITY, high = -INFINITY;
    for (std::size_t t = begin; t < end; ++t)
      for (const Corner& c : rm.corners[t]) low = std::min(low, rm.azimuth(c)), high = std::max(high, rm.azimuth(c));
    const int sectors = d.closed ? 1 : std::max(1, static_cast<int>(std::ceil(std::abs(d.alpha) / max_sector_alpha)));
    const double width = (high - low) / sectors;
    const std::size_t first_chart = charts.size();
    for (int s = 0; s < sectors; ++s) {
      Development sector = d;
      if (!d.closed) sector.azimuth_origin = low + (s + 0.5) * width;
      charts.push_back({sector, {}});
    }
    for (std::size_t t = begin; t < end; ++t) {
      const auto& c = rm.corners[t];
      const double centroid = (rm.azimuth(c[0]) + rm.azimuth(c[1]) + rm.azimuth(c[2])) / 3.0;
      const int s = std::min(sectors - 1, static_cast<int>((centroid - low) / width));
      charts[first_chart + static_cast<std::size_t>(s)].triangles.push_back(t);
    }
  }
  return charts;
}

// A chart's own UVs (Å, scaled so that its smallest stretch σ2 is 1) and its triangles' UV indices.
struct ChartUvs {
  std::vector<glm::dvec2> uvs;
  std::vector<Triangle> uv_triangles;  // parallel to Chart::triangles
  glm::dvec2 low{INFINITY}, high{-INFINITY};
};

ChartUvs unroll(const RingMesh& rm, const Chart& chart) {
  ChartUvs out;
  std::map<std::pair<int, int>, std::uint32_t> index_of;
  for (const std::size_t t : chart.triangles) {
    Triangle uv{};
    for (int c = 0; c < 3; ++c) {
      const Corner key = chart_corner(rm, chart.development, rm.corners[t][c]);
      const auto [it, inserted] = index_of.try_emplace({key.ring, key.step}, static_cast<std::uint32_t>(out.uvs.size()));
      if (inserted) out.uvs.push_back(developed_uv(rm, chart.development, key));
      uv[c] = it->second;
    }
    out.uv_triangles.push_back(uv);
  }
  double smallest = INFINITY;
  for (std::size_t i = 0; i < chart.triangles.size(); ++i) {
    const Triangle& uv = out.uv_triangles[i];
    smallest = std::min(smallest, stretch(rm, chart.triangles[i], {out.uvs[uv[0]], out.uvs[uv[1]], out.uvs[uv[2]]}).minor);
  }
  // Multiplying UV by σ2 divides every stretch by it.
  for (glm::dvec2& uv : out.uvs) {
    uv *= smallest;
    out.low = glm::min(out.low, uv);
    out.high = glm::max(out.high, uv);
  }
  return out;
}

// Shelf packing: charts by decreasing height, left to right in rows about as wide as the layout is
// tall (but at least as wide as the widest chart), a gutter around each. Returns each chart's
// translation, and the side of the square that holds them in `side`.
std::vector<glm::dvec2> pack(const std::vector<ChartUvs>& charts, double& side) {
  std::vector<std::size_t> order(charts.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto size = [&](std::size_t i) { return charts[i].high - charts[i].low; };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return size(a).y > size(b).y; });
  double widest_chart = 0.0, box_area = 0.0;
  for (std::size_t i = 0; i < charts.size(); ++i) {
    widest_chart = std::max(widest_chart, size(i).x);
    box_area += size(i).x * size(i).y;
  }
  const double row_width = std::max(widest_chart, std::sqrt(box_area));
  const double gutter = layout_gutter * row_width;
  std::vector<glm::dvec2> offset(charts.size());
  glm::dvec2 cursor(gutter);
  double row_height = 0.0;
  side = 0.0;
  for (const std::size_t i : order) {
    if (cursor.x > gutter && cursor.x + size(i).x > gutter + row_width) {
      cursor = {gutter, cursor.y + row_height + gutter};
      row_height = 0.0;
    }
    offset[i] = cursor - charts[i].low;
    side = std::max({side, cursor.x + size(i).x + gutter, cursor.y + size(i).y + gutter});
    cursor.x += size(i).x + gutter;
    row_height = std::max(row_height, size(i).y);
  }
  return offset;
}

void add_uvs(RingMesh& rm) {
  const std::vector<Chart> charts = make_charts(rm, choose_bands(rm));
  std::vector<ChartUvs> unrolled;
  for (const Chart& chart : charts) unrolled.push_back(unroll(rm, chart));
  double side = 0.0;
  const std::vector<glm::dvec2> offset = pack(unrolled, side);
  ProxyMesh& mesh = rm.mesh;
  mesh.uv_triangles.resize(mesh.triangles.size());
  for (std::size_t c = 0; c < charts.size(); ++c) {
    const auto first = static_cast<std::uint32_t>(mesh.uvs.size());
    for (const glm::dvec2& uv : unrolled[c].uvs) mesh.uvs.push_back((uv + offset[c]) / side);
    for (std::size_t i = 0; i < charts[c].triangles.size(); ++i) {
      const Triangle& local = unrolled[c].uv_triangles[i];
      mesh.uv_triangles[charts[c].triangles[i]] = {first + local[0], first + local[1], first + local[2]};
    }
  }
}

}  // namespace

ProxyMesh make_rbc_mesh(int target_triangles, const EvansFungShape& shape) {
  if (target_triangles < 200)
    throw InputError("", "--triangles", "the red blood cell needs at least 200 triangles, got " + std::to_string(target_triangles));
  const MeridianTable table = tabulate(shape);
  // Start from the flat-disk estimate (area ≈ 2πR0², equilateral triangles), then correct the
  // edge length by the square root of the count ratio until within 5% of the target.
  double edge = std::sqrt(4.0 * 2.0 * pi * shape.r0 * shape.r0 / (std::sqrt(3.0) * target_triangles));
  RingMesh rings = build(shape, table, edge);
  for (int iteration = 0; iteration < 8; ++iteration) {
    const double ratio = static_cast<double>(rings.mesh.triangles.size()) / target_triangles;
    if (std::abs(ratio - 1.0) < 0.05) break;
    edge *= std::sqrt(ratio);
    rings = build(shape, table, edge);
  }
  add_uvs(rings);
  compute_angle_weighted_normals(rings.mesh);
  return std::move(rings.mesh);
}

}  // namespace nano::mesh
