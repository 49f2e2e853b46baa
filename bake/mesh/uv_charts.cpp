#include "bake/mesh/uv_charts.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <set>
#include <unordered_set>

#include <glm/geometric.hpp>

#include "bake/mesh/chart_parameterization.hpp"
#include "common/error.hpp"

namespace nano::mesh {
namespace {

using glm::dvec2;
using glm::dvec3;
constexpr std::uint32_t kNone = ~0u;

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) { return (std::uint64_t{a} << 32) | b; }

// Faces with their unit normals, areas, centroids and the face across each edge (corners k, k+1).
struct Surface {
  const ProxyMesh& mesh;
  std::vector<dvec3> normal, centroid;
  std::vector<double> area;
  std::vector<std::array<std::uint32_t, 3>> across;

  // The mesh's own faults are refused from `source` (the mesh file), naming the triangle or edge.
  Surface(const ProxyMesh& m, const InputSource& source) : mesh(m) {
    const std::size_t n = m.triangles.size();
    if (n == 0 || n >= kNone)
      source.fail("cannot make UV charts: they need a mesh of 1 to 2^32 − 1 triangles, this one has " + std::to_string(n));
    normal.resize(n), centroid.resize(n), area.resize(n), across.assign(n, {kNone, kNone, kNone});
    std::unordered_map<std::uint64_t, std::uint32_t> directed;  // directed edge → face
    directed.reserve(3 * n);
    for (std::uint32_t f = 0; f < n; ++f) {
      const Triangle& t = m.triangles[f];
      const dvec3 a = m.positions[t[0]], b = m.positions[t[1]], c = m.positions[t[2]];
      const dvec3 cross = glm::cross(b - a, c - a);
      area[f] = 0.5 * glm::length(cross);
      if (!(area[f] > 0)) source.fail("cannot make UV charts: triangle " + std::to_string(f) + " has zero area");
      normal[f] = cross / (2 * area[f]);
      centroid[f] = (a + b + c) / 3.0;
      for (int k = 0; k < 3; ++k)
        if (!directed.emplace(edge_key(t[k], t[(k + 1) % 3]), f).second)
          source.fail("cannot make UV charts: edge " + std::to_string(t[k]) + "–" + std::to_string(t[(k + 1) % 3]) +
                      " of triangle " + std::to_string(f) + " is non-manifold or inconsistently oriented");
    }
    for (std::uint32_t f = 0; f < n; ++f) {
      const Triangle& t = m.triangles[f];
      for (int k = 0; k < 3; ++k)
        if (const auto it = directed.find(edge_key(t[(k + 1) % 3], t[k])); it != directed.end()) across[f][k] = it->second;
    }
  }
  std::size_t size() const { return area.size(); }
};

// Connected pieces of `faces` (joined across edges inside the set), each in ascending face order.
std::vector<std::vector<std::uint32_t>> components(const Surface& s, const std::vector<std::uint32_t>& faces) {
  std::unordered_set<std::uint32_t> left(faces.begin(), faces.end());
  std::vector<std::uint32_t> sorted = faces;
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::vector<std::uint32_t>> out;
  for (std::uint32_t seed : sorted) {
    if (!left.erase(seed)) continue;
    std::vector<std::uint32_t> piece{seed};
    for (std::size_t i = 0; i < piece.size(); ++i)
      for (std::uint32_t g : s.across[piece[i]])
        if (g != kNone && left.erase(g)) piece.push_back(g);
    std::sort(piece.begin(), piece.end());
    out.push_back(std::move(piece));
  }
  return out;
}

// A topological disk: one border loop, Euler characteristic 1, and no vertex where two fans of
// the chart touch (such a vertex has four or more border edges).
bool is_disk(const Surface& s, const std::vector<std::uint32_t>& faces) {
  const std::unordered_set<std::uint32_t> in(faces.begin(), faces.end());
  std::unordered_map<std::uint32_t, int> border_degree;
  std::unordered_set<std::uint32_t> vertices;
  std::unordered_map<std::uint32_t, std::uint32_t> next;  // border walk: a border edge's start → end
  std::size_t interior_half_edges = 0, border_edges = 0;
  for (std::uint32_t f : faces) {
    const Triangle& t = s.mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      vertices.insert(t[k]);
      const std::uint32_t g = s.across[f][k];
      if (g != kNone && in.count(g)) {
        ++interior_half_edges;
        continue;
      }
      ++border_edges;
      ++border_degree[t[k]], ++border_degree[t[(k + 1) % 3]];
      next[t[k]] = t[(k + 1) % 3];
    }
  }
  if (border_edges == 0) return false;
  for (const auto& [v, degree] : border_degree)
    if (degree != 2) return false;
  const std::size_t edges = interior_half_edges / 2 + border_edges;
  if (std::int64_t(vertices.size()) - std::int64_t(edges) + std::int64_t(faces.size()) != 1) return false;
  // One loop: walking from any border vertex returns after every border edge.
  std::size_t steps = 0;
  const std::uint32_t start = next.begin()->first;
  std::uint32_t v = start;
  do {
    v = next.at(v);
    ++steps;
  } while (v != start && steps <= border_edges);
  return steps == border_edges;
}

// The faces cut in two at the median of their centroids along the direction they spread most.
std::array<std::vector<std::uint32_t>, 2> bisect(const Surface& s, const std::vector<std::uint32_t>& faces) {
  dvec3 mean(0.0);
  for (std::uint32_t f : faces) mean += s.centroid[f];
  mean /= double(faces.size());
  double c[3][3] = {};
  for (std::uint32_t f : faces) {
    const dvec3 d = s.centroid[f] - mean;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) c[i][j] += d[i] * d[j];
  }
  // Power iteration from the box's longest side: the principal axis to a few digits is plenty.
  dvec3 axis(1, 0, 0);
  for (int i = 1; i < 3; ++i)
    if (c[i][i] > c[0][0] && c[i][i] >= c[(i + 1) % 3][(i + 1) % 3]) axis = dvec3(0), axis[i] = 1;
  for (int it = 0; it < 32; ++it) {
    dvec3 next(0.0);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) next[i] += c[i][j] * axis[j];
    if (!(glm::length(next) > 0)) break;
    axis = glm::normalize(next);
  }
  std::vector<std::pair<double, std::uint32_t>> order;
  for (std::uint32_t f : faces) order.push_back({glm::dot(s.centroid[f] - mean, axis), f});
  std::sort(order.begin(), order.end());
  std::array<std::vector<std::uint32_t>, 2> halves;
  for (std::size_t i = 0; i < order.size(); ++i) halves[i < order.size() / 2 ? 0 : 1].push_back(order[i].second);
  return halves;
}

double signed_area(dvec2 a, dvec2 b, dvec2 c) { return 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)); }

// max(σ1, 1/σ2) of the linear map taking the surface triangle onto its UV triangle.
double triangle_stretch(const dvec3 p[3], const dvec2 q[3]) {
  const dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
  const double l1 = glm::length(e1);
  const dvec3 x = e1 / l1;
  const dvec3 y = glm::normalize(e2 - glm::dot(e2, x) * x);
  // Surface triangle in its own plane: (0, 0), (l1, 0), (a, b).
  const double a = glm::dot(e2, x), b = glm::dot(e2, y);
  const dvec2 d1 = q[1] - q[0], d2 = q[2] - q[0];
  // J · [l1 a; 0 b] = [d1 d2]  →  J = [d1 d2] · [1/l1, −a/(l1 b); 0, 1/b].
  const dvec2 j0 = d1 / l1, j1 = (d2 - d1 * (a / l1)) / b;
  const double e = 0.5 * (glm::dot(j0, j0) + glm::dot(j1, j1));
  const double det = j0.x * j1.y - j0.y * j1.x;
  const double root = std::sqrt(std::max(0.0, e * e - det * det));
  const double s1 = std::sqrt(e + root), s2 = std::sqrt(std::max(0.0, e - root));
  return s2 > 0 ? std::max(s1, 1.0 / s2) : INFINITY;
}

// Interiors of two UV triangles (counter-clockwise) overlap: no separating edge axis, each
// triangle shrunk a hair toward its centroid so neighbours sharing an edge or a corner pass.
bool interiors_overlap(std::array<dvec2, 3> a, std::array<dvec2, 3> b) {
  for (auto* t : {&a, &b}) {
    const dvec2 centre = ((*t)[0] + (*t)[1] + (*t)[2]) / 3.0;
    for (dvec2& p : *t) p = centre + (p - centre) * (1 - 1e-7);
  }
  for (const auto* t : {&a, &b})
    for (int k = 0; k < 3; ++k) {
      const dvec2 p = (*t)[k], q = (*t)[(k + 1) % 3];
      const auto& other = t == &a ? b : a;
      bool all_outside = true;
      for (const dvec2& r : other) all_outside = all_outside && signed_area(p, q, r) <= 0;
      if (all_outside) return false;
    }
  return true;
}

struct Flattened {
  std::vector<std::uint32_t> faces;
  std::vector<std::uint32_t> vertices;  // local → mesh position index
  std::vector<Triangle> local;          // per face, local vertex indices
  std::vector<dvec2> uv;                // per local vertex, Å (area kept)
  double area = 0.0, max_stretch = 1.0, weighted_stretch = 0.0;
  std::string method;
};

// Accepts a chart's UVs when every triangle keeps one orientation (mirrored as a whole is
// flipped back), no two interiors overlap and the stretch, once the chart keeps its area, is
// within the bound. Scales the UVs to Å.
bool accept(Flattened& chart, const Surface& s, std::vector<dvec2> uv, double max_stretch) {
  double uv_area = 0;
  int positive = 0, negative = 0;
  for (const Triangle& t : chart.local) {
    const double a = signed_area(uv[t[0]], uv[t[1]], uv[t[2]]);
    uv_area += a;
    positive += a > 0, negative += a < 0;
  }
  if (positive != 0 && negative != 0) return false;
  if (positive + negative != int(chart.local.size())) return false;  // a zero-area UV triangle
  const double flip = negative ? -1.0 : 1.0;
  const double scale = std::sqrt(chart.area / std::abs(uv_area));
  for (dvec2& p : uv) p = dvec2(flip * p.x, p.y) * scale;
  chart.max_stretch = 1.0, chart.weighted_stretch = 0.0;
  for (std::size_t i = 0; i < chart.local.size(); ++i) {
    const Triangle& t = chart.local[i];
    const dvec3 p[3] = {s.mesh.positions[chart.vertices[t[0]]], s.mesh.positions[chart.vertices[t[1]]],
                        s.mesh.positions[chart.vertices[t[2]]]};
    const dvec2 q[3] = {uv[t[0]], uv[t[1]], uv[t[2]]};
    const double stretch = triangle_stretch(p, q);
    if (!(stretch <= max_stretch)) return false;
    chart.max_stretch = std::max(chart.max_stretch, stretch);
    chart.weighted_stretch += stretch * s.area[chart.faces[i]];
  }
  // Overlaps: triangles binned by their UV boxes on a grid of about one triangle per cell.
  dvec2 lo(INFINITY), hi(-INFINITY);
  for (const dvec2& p : uv) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const double cell = std::max(1e-9, std::sqrt((hi.x - lo.x) * (hi.y - lo.y) / double(chart.local.size())));
  const auto cells = [&](double v, double origin) { return std::int64_t(std::floor((v - origin) / cell)); };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
  for (std::uint32_t i = 0; i < chart.local.size(); ++i) {
    const Triangle& t = chart.local[i];
    const dvec2 a = glm::min(glm::min(uv[t[0]], uv[t[1]]), uv[t[2]]), b = glm::max(glm::max(uv[t[0]], uv[t[1]]), uv[t[2]]);
    for (std::int64_t x = cells(a.x, lo.x); x <= cells(b.x, lo.x); ++x)
      for (std::int64_t y = cells(a.y, lo.y); y <= cells(b.y, lo.y); ++y) {
        std::vector<std::uint32_t>& bin = grid[(std::uint64_t(x) << 32) ^ std::uint64_t(y)];
        for (std::uint32_t j : bin) {
          const Triangle& u = chart.local[j];
          if (interiors_overlap({uv[t[0]], uv[t[1]], uv[t[2]]}, {uv[u[0]], uv[u[1]], uv[u[2]]})) return false;
        }
        bin.push_back(i);
      }
  }
  chart.uv = std::move(uv);
  return true;
}

// A disk chart flattened by LSCM, else by mean-value coordinates; nothing when neither passes.
std::optional<Flattened> flatten(const Surface& s, const std::vector<std::uint32_t>& faces, double max_stretch) {
  Flattened chart;
  chart.faces = faces;
  std::unordered_map<std::uint32_t, std::uint32_t> local;
  std::vector<dvec3> positions;
  for (std::uint32_t f : faces) {
    Triangle t{};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = s.mesh.triangles[f][k];
      const auto [it, added] = local.try_emplace(v, std::uint32_t(chart.vertices.size()));
      if (added) chart.vertices.push_back(v), positions.push_back(s.mesh.positions[v]);
      t[k] = it->second;
    }
    chart.local.push_back(t);
    chart.area += s.area[f];
  }
  if (faces.size() == 1) {  // a triangle is its own isometric chart
    const dvec3 e1 = positions[1] - positions[0], e2 = positions[2] - positions[0];
    const dvec3 x = glm::normalize(e1), y = glm::normalize(e2 - glm::dot(e2, x) * x);
    chart.method = "isometric (one triangle)";
    if (accept(chart, s, {dvec2(0), dvec2(glm::length(e1), 0), dvec2(glm::dot(e2, x), glm::dot(e2, y))}, INFINITY))
      return chart;
    return std::nullopt;
  }
  for (ChartMethod method : {ChartMethod::lscm, ChartMethod::mean_value}) {
    std::optional<std::vector<dvec2>> uv = parameterize_chart(positions, chart.local, method);
    if (!uv) continue;
    chart.method = to_string(method);
    if (accept(chart, s, std::move(*uv), max_stretch)) return chart;
  }
  return std::nullopt;
}

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Charts grown over edges from seed faces, a face joining while its normal lies within the
// angle of the seed's; seeds in face order from a start the seed picks.
std::vector<std::vector<std::uint32_t>> grow_charts(const Surface& s, double cos_limit, std::uint64_t seed) {
  const std::size_t n = s.size();
  std::vector<std::uint32_t> chart_of(n, kNone);
  std::vector<std::vector<std::uint32_t>> charts;
  const std::size_t start = splitmix64(seed) % n;
  for (std::size_t i = 0; i < n; ++i) {
    const auto f0 = std::uint32_t((start + i) % n);
    if (chart_of[f0] != kNone) continue;
    const auto c = std::uint32_t(charts.size());
    std::vector<std::uint32_t> faces{f0};
    chart_of[f0] = c;
    for (std::size_t k = 0; k < faces.size(); ++k)
      for (std::uint32_t g : s.across[faces[k]])
        if (g != kNone && chart_of[g] == kNone && glm::dot(s.normal[g], s.normal[f0]) >= cos_limit)
          chart_of[g] = c, faces.push_back(g);
    charts.push_back(std::move(faces));
  }
  return charts;
}

// Greedy growth leaves slivers of charts between the big ones. Neighbouring charts merge, the
// pair whose union stays nearest its mean normal first, while every face of the union lies within
// the angle of that mean (area-weighted normal): the charts a cone of that angle allows, fewer seams.
void merge_charts(const Surface& s, std::vector<std::vector<std::uint32_t>>& charts, double cos_limit) {
  std::vector<std::uint32_t> chart_of(s.size());
  std::vector<dvec3> normal_sum(charts.size(), dvec3(0.0));
  for (std::uint32_t c = 0; c < charts.size(); ++c)
    for (std::uint32_t f : charts[c]) chart_of[f] = c, normal_sum[c] += s.normal[f] * s.area[f];
  const auto worst_cos = [&](std::uint32_t a, std::uint32_t b) {  // smallest cos to the union's mean
    const dvec3 sum = normal_sum[a] + normal_sum[b];
    if (!(glm::length(sum) > 0)) return -1.0;
    const dvec3 axis = glm::normalize(sum);
    double worst = 1.0;
    for (std::uint32_t c : {a, b})
      for (std::uint32_t f : charts[c]) worst = std::min(worst, glm::dot(s.normal[f], axis));
    return worst;
  };
  for (;;) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for (std::uint32_t f = 0; f < s.size(); ++f)
      for (std::uint32_t g : s.across[f])
        if (g != kNone && chart_of[f] != chart_of[g]) pairs.insert(std::minmax(chart_of[f], chart_of[g]));
    double best = cos_limit;
    std::pair<std::uint32_t, std::uint32_t> chosen{kNone, kNone};
    for (const auto& [a, b] : pairs)
      if (const double w = worst_cos(a, b); w >= best && (chosen.first == kNone || w > best)) best = w, chosen = {a, b};
    if (chosen.first == kNone) break;
    const auto [keep, gone] = chosen;
    for (std::uint32_t f : charts[gone]) chart_of[f] = keep;
    charts[keep].insert(charts[keep].end(), charts[gone].begin(), charts[gone].end());
    charts[gone].clear();
    normal_sum[keep] += normal_sum[gone];
    normal_sum[gone] = dvec3(0.0);
  }
  std::erase_if(charts, [](const std::vector<std::uint32_t>& c) { return c.empty(); });
}

// Growth by a normal cone leaves ragged borders on faceted surfaces (alternate faces in and
// out), and a vertex where a chart's faces meet only at a corner makes the chart no disk. A face
// whose neighbours across two or three edges all belong to one other chart joins it; a few passes
// straighten the borders.
void smooth_borders(const Surface& s, std::vector<std::vector<std::uint32_t>>& charts) {
  std::vector<std::uint32_t> chart_of(s.size());
  for (std::uint32_t c = 0; c < charts.size(); ++c)
    for (std::uint32_t f : charts[c]) chart_of[f] = c;
  for (int pass = 0; pass < 4; ++pass) {
    bool changed = false;
    for (std::uint32_t f = 0; f < s.size(); ++f) {
      const auto& n = s.across[f];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = n[k], b = n[(k + 1) % 3];
        if (a == kNone || b == kNone) continue;
        const std::uint32_t other = chart_of[a];
        if (other != chart_of[f] && chart_of[b] == other) {
          chart_of[f] = other, changed = true;
          break;
        }
      }
    }
    if (!changed) break;
  }
  for (auto& c : charts) c.clear();
  for (std::uint32_t f = 0; f < s.size(); ++f) charts[chart_of[f]].push_back(f);
  std::erase_if(charts, [](const std::vector<std::uint32_t>& c) { return c.empty(); });
}

// Each chart rotated to its principal axes (a tighter box) and placed on shelves, tallest first,
// `gutter` Å apart and from the square's sides; returns the atlas edge in Å.
double pack(std::vector<Flattened>& charts, double gutter) {
  std::vector<dvec2> size(charts.size());
  double box_area = 0, widest = 0;
  for (std::size_t c = 0; c < charts.size(); ++c) {
    std::vector<dvec2>& uv = charts[c].uv;
    dvec2 mean(0.0);
    for (const dvec2& p : uv) mean += p;
    mean /= double(uv.size());
    double xx = 0, xy = 0, yy = 0;
    for (const dvec2& p : uv) {
      const dvec2 d = p - mean;
      xx += d.x * d.x, xy += d.x * d.y, yy += d.y * d.y;
    }
    const double angle = 0.5 * std::atan2(2 * xy, xx - yy);
    const double cs = std::cos(angle), sn = std::sin(angle);
    dvec2 lo(INFINITY), hi(-INFINITY);
    for (dvec2& p : uv) {
      const dvec2 d = p - mean;
      p = dvec2(cs * d.x + sn * d.y, -sn * d.x + cs * d.y);  // a rotation keeps the orientation
      lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    for (dvec2& p : uv) p -= lo;
    size[c] = hi - lo;
    box_area += (size[c].x + gutter) * (size[c].y + gutter);
    widest = std::max(widest, size[c].x);
  }
  std::vector<std::size_t> order(charts.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return size[a].y > size[b].y; });
  // Shelves of a given width; the atlas is the square around them, so the width that makes the
  // squarest stack wins (tried from the widest chart to twice the square root of the boxes' area).
  const auto shelve = [&](double row, std::vector<dvec2>* place) {
    double x = gutter, y = gutter, shelf = 0, right = 0;
    for (std::size_t c : order) {
      if (x > gutter && x + size[c].x + gutter > row) y += shelf + gutter, x = gutter, shelf = 0;
      if (place) (*place)[c] = dvec2(x, y);
      x += size[c].x + gutter;
      right = std::max(right, x);
      shelf = std::max(shelf, size[c].y);
    }
    return std::max(right, y + shelf + gutter);
  };
  const double narrowest = widest + 2 * gutter, broadest = std::max(narrowest, 2 * std::sqrt(box_area));
  double best_row = narrowest, best_edge = INFINITY;
  for (int k = 0; k <= 32; ++k) {
    const double row = narrowest + (broadest - narrowest) * k / 32.0;
    if (const double edge = shelve(row, nullptr); edge < best_edge) best_edge = edge, best_row = row;
  }
  std::vector<dvec2> place(charts.size());
  shelve(best_row, &place);
  for (std::size_t c = 0; c < charts.size(); ++c)
    for (dvec2& p : charts[c].uv) p += place[c];
  return best_edge;
}

}  // namespace

ChartAtlas generate_uv_charts(ProxyMesh& mesh, const InputSource& source, const ChartOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  // Invariants, not input: the options are the baker's own constants (and tests'), never read from a file.
  if (!(options.max_normal_angle_degrees > 0 && options.max_normal_angle_degrees < 90))
    throw std::invalid_argument("generate_uv_charts: the charts' normal angle must lie in (0°, 90°)");
  if (!(options.max_stretch >= 1)) throw std::invalid_argument("generate_uv_charts: the stretch bound must be at least 1");
  const Surface s(mesh, source);
  const double cos_limit = std::cos(options.max_normal_angle_degrees * M_PI / 180.0);
  std::deque<std::vector<std::uint32_t>> pending;
  std::vector<std::vector<std::uint32_t>> grown = grow_charts(s, cos_limit, options.seed);
  merge_charts(s, grown, cos_limit);
  smooth_borders(s, grown);
  for (auto& chart : grown) pending.push_back(std::move(chart));
  std::vector<Flattened> charts;
  while (!pending.empty()) {
    std::vector<std::uint32_t> faces = std::move(pending.front());
    pending.pop_front();
    if (is_disk(s, faces))
      if (std::optional<Flattened> flat = flatten(s, faces, options.max_stretch)) {
        charts.push_back(std::move(*flat));
        continue;
      }
    for (const std::vector<std::uint32_t>& half : bisect(s, faces))
      for (std::vector<std::uint32_t>& piece : components(s, half)) pending.push_back(std::move(piece));
  }
  double edge_sum = 0;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) edge_sum += glm::length(mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]]);
  const double gutter = options.gutter > 0 ? options.gutter : 0.5 * edge_sum / (3.0 * double(mesh.triangles.size()));
  const double edge = pack(charts, gutter);

  ChartAtlas atlas;
  atlas.uv_scale = edge;
  mesh.uvs.clear();
  mesh.uv_triangles.assign(mesh.triangles.size(), Triangle{});
  std::vector<std::uint32_t> chart_of(mesh.triangles.size(), kNone);
  double total_area = 0, weighted = 0;
  for (std::size_t c = 0; c < charts.size(); ++c) {
    const Flattened& chart = charts[c];
    const auto first = std::uint32_t(mesh.uvs.size());
    for (const dvec2& p : chart.uv) mesh.uvs.push_back(p / edge);
    for (std::size_t i = 0; i < chart.faces.size(); ++i) {
      const Triangle& t = chart.local[i];
      mesh.uv_triangles[chart.faces[i]] = {first + t[0], first + t[1], first + t[2]};
      chart_of[chart.faces[i]] = std::uint32_t(c);
    }
    atlas.charts.push_back({chart.faces.size(), chart.area, chart.max_stretch, chart.method});
    atlas.max_stretch = std::max(atlas.max_stretch, chart.max_stretch);
    total_area += chart.area, weighted += chart.weighted_stretch;
  }
  atlas.mean_stretch = weighted / total_area;
  atlas.packing_efficiency = total_area / (edge * edge);
  for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t g = s.across[f][k];
      if (g != kNone && f < g && chart_of[f] != chart_of[g])
        atlas.seam_length += glm::length(mesh.positions[mesh.triangles[f][(k + 1) % 3]] - mesh.positions[mesh.triangles[f][k]]);
    }
  atlas.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return atlas;
}

nlohmann::json to_json(const ChartAtlas& atlas) {
  nlohmann::json charts = nlohmann::json::array();
  for (const ChartSummary& c : atlas.charts)
    charts.push_back({{"triangles", c.triangles}, {"area", c.area}, {"max_stretch", c.max_stretch}, {"method", c.method}});
  return {{"charts", atlas.charts.size()},
          {"seam_length", atlas.seam_length},
          {"max_stretch", atlas.max_stretch},
          {"mean_stretch", atlas.mean_stretch},
          {"packing_efficiency", atlas.packing_efficiency},
          {"uv_scale", atlas.uv_scale},
          {"seconds", atlas.seconds},
          {"per_chart", charts}};
}

}  // namespace nano::mesh
