#include "bake/grid/exclusion_field.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <mutex>
#include <string>
#include <utility>

#include "bake/grid/triangle_distance.hpp"
#include "common/error.hpp"
#include "common/parallel_for.hpp"
#include "shaders/shared/medium.h"

namespace nano::grid {
namespace {

// Where each cell is sampled (fractions of the cell): its centre, three face centres and points
// spread through it, deterministic.
constexpr std::array<glm::dvec3, 9> kSamples{{{0.5, 0.5, 0.5},
                                              {0.5, 0.5, 0.0},
                                              {0.5, 0.0, 0.5},
                                              {0.0, 0.5, 0.5},
                                              {0.25, 0.25, 0.25},
                                              {0.75, 0.75, 0.25},
                                              {0.75, 0.25, 0.75},
                                              {0.25, 0.75, 0.75},
                                              {0.5, 0.25, 0.75}}};

gpu::ExclusionField record_of(const ExclusionField& f) {
  gpu::ExclusionField r{};
  r.origin = glm::vec4(glm::vec3(f.origin), static_cast<float>(f.spacing));
  r.dims = glm::uvec4(glm::uvec3(f.dims), 0u);
  r.limits = glm::vec4(0.0f, static_cast<float>(f.clamp), 1.0f / static_cast<float>(f.spacing), 0.0f);
  return r;
}

}  // namespace

DrawnClearance::DrawnClearance(const MeshSurface& surface, std::vector<float> reach) : surface_(surface), reach_(std::move(reach)) {
  const std::size_t triangles = surface.mesh().triangles.size();
  if (reach_.empty()) reach_.assign(triangles, 0.f);
  if (reach_.size() != triangles)
    throw InputError("", "exclusion field", std::to_string(reach_.size()) + " reaches for " + std::to_string(triangles) + " triangles");
  least_ = std::numeric_limits<double>::infinity();
  for (const float r : reach_) {
    if (!(r >= 0.f && std::isfinite(r))) throw InputError("", "exclusion field", "a triangle's reach is " + std::to_string(r));
    least_ = std::min(least_, double(r)), largest_ = std::max(largest_, double(r));
  }
  // At most 1 % of the triangles (or 32) are tall.
  std::vector<float> sorted = reach_;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t tall = std::min(sorted.size(), std::max<std::size_t>(32, sorted.size() / 100));
  common_largest_ = sorted.size() > tall ? sorted[sorted.size() - 1 - tall] : least_;
  const mesh::ProxyMesh& mesh = surface.mesh();
  for (std::uint32_t t = 0; t < reach_.size(); ++t) {
    if (!(reach_[t] > common_largest_)) continue;
    glm::dvec3 centre(0.0);
    for (int c = 0; c < 3; ++c) centre += mesh.corner_position(t, c) / 3.0;
    double radius = 0.0;
    for (int c = 0; c < 3; ++c) radius = std::max(radius, glm::length(mesh.corner_position(t, c) - centre));
    tall_.push_back({t, centre, radius});
  }
}

double DrawnClearance::at(const glm::dvec3& p, double enough) const {
  const double d = std::sqrt(surface_.squared_distance(p));
  return surface_.contains(p) ? inside(p, d, enough) : outside(p, d, enough);
}

double DrawnClearance::inside(const glm::dvec3& p, double distance, double enough) const {
  // The value is at most −(distance + least): at or below −enough it is clamped there unsearched.
  if (distance + least_ >= enough) return -enough;
  return outside(p, distance, enough) - 2.0 * distance;
}

// A triangle t lowers the value below best only when nearer than best + reach[t]: the tall ones are
// tried one by one (after a bounding-sphere test), the others through one box query of half-size
// best + the largest common reach (none is nearer than the mesh's distance).
double DrawnClearance::outside(const glm::dvec3& p, double distance, double enough) const {
  if (largest_ == least_ || distance - largest_ >= enough) return std::min(distance - largest_, enough);
  const mesh::ProxyMesh& mesh = surface_.mesh();
  double best = enough;
  const auto offer = [&](std::uint32_t t) {
    const double within = best + double(reach_[t]);
    if (within <= 0.0) return;
    const mesh::Triangle& tri = mesh.triangles[t];
    const double d2 = squared_distance_to_triangle(p, mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]);
    if (d2 < within * within) best = std::min(best, std::sqrt(d2) - double(reach_[t]));
  };
  for (const Tall& t : tall_)
    if (glm::length(p - t.centre) - t.radius < best + double(reach_[t.triangle])) offer(t.triangle);
  // The nearest triangle alone brings the value to distance − least at most, so it is searched for
  // too (with a hair of room for the rounding of `distance`).
  const double r = std::min(best, distance - least_) + common_largest_ + 1e-9 * (1.0 + distance);
  if (r < distance) return best;
  for (const std::uint32_t t : surface_.triangles_meeting(p - glm::dvec3(r), p + glm::dvec3(r)))
    if (reach_[t] <= common_largest_) offer(t);
  return best;
}

double interpolated_clearance(const ExclusionField& field, const glm::dvec3& p) {
  const gpu::ExclusionField r = record_of(field);
  glm::ivec3 cell;
  glm::vec3 frac;
  if (!gpu::exclusion_cell(r, glm::vec3(p), cell, frac)) return field.clamp;
  float corners[8];
  for (int c = 0; c < 8; ++c)
    corners[c] = field.values[gpu::exclusion_node(r, cell + glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1))];
  return gpu::exclusion_trilinear(corners, frac);
}

namespace {

// The grid: the mesh's box grown by every reach and two spacings, at the coarsest spacing
// (≥ min_spacing) whose nodes fit the budget.
ExclusionField lay_out_grid(const mesh::ProxyMesh& mesh, const DrawnClearance& clearance, const ExclusionFieldRequest& request) {
  if (mesh.positions.empty()) throw InputError("", "", "an exclusion field needs a mesh with vertices");
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const glm::dvec3& v : mesh.positions) lo = glm::min(lo, v), hi = glm::max(hi, v);
  const double grow = clearance.largest_reach() + request.medium_reach;
  lo -= grow, hi += grow;
  ExclusionField f;
  const glm::dvec3 size = hi - lo;
  f.spacing = std::max(request.min_spacing, std::cbrt(size.x * size.y * size.z / static_cast<double>(request.max_nodes)));
  const auto nodes_at = [&](double h) { return glm::ivec3(glm::ceil(size / h)) + glm::ivec3(5); };  // two spacings each side
  for (glm::ivec3 n = nodes_at(f.spacing); double(n.x) * n.y * n.z > double(request.max_nodes); n = nodes_at(f.spacing))
    f.spacing *= 1.02;
  f.dims = nodes_at(f.spacing);
  f.origin = lo - 2.0 * f.spacing;
  f.clamp = request.medium_reach + 4.0 * f.spacing;
  f.least_reach = clearance.least_reach();
  f.largest_reach = clearance.largest_reach();
  return f;
}

glm::dvec3 node_position(const ExclusionField& f, std::size_t n) {
  const std::size_t plane = std::size_t(f.dims.x) * f.dims.y;
  return f.origin + f.spacing * glm::dvec3(double(n % f.dims.x), double(n / f.dims.x % f.dims.y), double(n / plane));
}

// Every node's side of the surface (−1 inside, +1 outside). Distances everywhere; the inside test
// only near the surface: a node farther than one spacing from it shares its side with every such
// neighbour (the segment between them stays more than half a spacing from the surface), so far
// nodes take their side from one test per connected component.
std::vector<std::int8_t> node_sides(const MeshSurface& surface, const ExclusionField& f, int threads, std::vector<double>& distance) {
  const std::size_t count = static_cast<std::size_t>(f.dims.x) * f.dims.y * f.dims.z;
  distance.assign(count, 0.0);
  std::vector<std::int8_t> side(count, 0);
  parallel_for(static_cast<std::size_t>(f.dims.z), threads, [&](std::size_t k) {
    for (std::size_t n = k * f.dims.x * f.dims.y; n < (k + 1) * f.dims.x * f.dims.y; ++n) {
      const glm::dvec3 p = node_position(f, n);
      distance[n] = std::sqrt(surface.squared_distance(p));
      if (distance[n] <= f.spacing) side[n] = surface.contains(p) ? -1 : 1;
    }
  });
  std::deque<std::size_t> queue;
  const std::array<glm::ivec3, 6> steps{{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};
  for (std::size_t start = 0; start < count; ++start) {
    if (side[start] != 0) continue;
    const std::int8_t s = surface.contains(node_position(f, start)) ? -1 : 1;
    side[start] = s;
    queue.push_back(start);
    while (!queue.empty()) {
      const std::size_t n = queue.front();
      queue.pop_front();
      const glm::ivec3 at(int(n % f.dims.x), int(n / f.dims.x % f.dims.y), int(n / (std::size_t(f.dims.x) * f.dims.y)));
      for (const glm::ivec3& step : steps) {
        const glm::ivec3 m = at + step;
        if (glm::any(glm::lessThan(m, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(m, f.dims))) continue;
        const std::size_t mi = f.node_index(m.x, m.y, m.z);
        if (side[mi] != 0) continue;
        side[mi] = s;
        queue.push_back(mi);
      }
    }
  }
  return side;
}

// The most the interpolated value exceeds the exact one, sampled where a decision can go wrong:
// cells that can keep a copy (some corner above 0) and whose true clearance can fall below the
// largest threshold (some corner below it plus the distance from a point of the cell to its
// nearest corner), at points whose interpolated value is above 0. That is enough: where the rule
// keeps a copy, value − margin ≥ r + clearance > 0, so the value is above 0 there.
void measure_excess(const MeshSurface& surface, const DrawnClearance& clearance, const std::vector<std::int8_t>& side,
                    const ExclusionFieldRequest& request, ExclusionField& f) {
  const double near_threshold = request.medium_reach + f.spacing;
  std::mutex merge;
  std::atomic<std::size_t> samples{0};
  parallel_for(static_cast<std::size_t>(f.dims.z - 1), request.threads, [&](std::size_t k) {
    double excess = 0;
    std::size_t taken = 0;
    for (int j = 0; j + 1 < f.dims.y; ++j)
      for (int i = 0; i + 1 < f.dims.x; ++i) {
        float lowest = f.values[f.node_index(i, j, int(k))], highest = lowest;
        for (int c = 1; c < 8; ++c) {
          const float v = f.values[f.node_index(i + (c & 1), j + ((c >> 1) & 1), int(k) + ((c >> 2) & 1))];
          lowest = std::min(lowest, v), highest = std::max(highest, v);
        }
        if (!(highest > 0.0f && lowest < near_threshold)) continue;
        for (const glm::dvec3& t : kSamples) {
          const glm::dvec3 p = f.origin + f.spacing * (glm::dvec3(i, j, double(k)) + t);
          const double d = std::sqrt(surface.squared_distance(p));
          // Beyond one spacing from the surface p shares the side of its nearest node (within 0.87
          // spacings of it).
          const glm::ivec3 nearest = glm::ivec3(i, j, int(k)) + glm::ivec3(glm::round(t));
          const bool inside = d <= f.spacing ? surface.contains(p) : side[f.node_index(nearest.x, nearest.y, nearest.z)] < 0;
          const double interpolated = interpolated_clearance(f, p);
          // Only a value above 0 can keep a copy (every threshold is r + clearance > 0).
          if (interpolated <= 0.0) continue;
          const double exact = inside ? clearance.inside(p, d, f.clamp) : clearance.outside(p, d, f.clamp);
          excess = std::max(excess, interpolated - std::clamp(exact, -f.clamp, f.clamp));
          ++taken;
        }
      }
    samples += taken;
    const std::lock_guard lock(merge);
    f.measured_excess = std::max(f.measured_excess, excess);
  });
  f.samples = samples;
}

}  // namespace

ExclusionField bake_exclusion_field(const MeshSurface& surface, const ExclusionFieldRequest& request) {
  const DrawnClearance clearance(surface, request.reach);
  ExclusionField f = lay_out_grid(surface.mesh(), clearance, request);
  std::vector<double> distance;
  const std::vector<std::int8_t> side = node_sides(surface, f, request.threads, distance);
  f.values.resize(distance.size());
  const std::size_t plane = std::size_t(f.dims.x) * f.dims.y;
  parallel_for(static_cast<std::size_t>(f.dims.z), request.threads, [&](std::size_t k) {
    for (std::size_t n = k * plane; n < (k + 1) * plane; ++n) {
      const glm::dvec3 p = node_position(f, n);
      const double value = side[n] < 0 ? clearance.inside(p, distance[n], f.clamp) : clearance.outside(p, distance[n], f.clamp);
      f.values[n] = static_cast<float>(std::clamp(value, -f.clamp, f.clamp));
    }
  });
  measure_excess(surface, clearance, side, request, f);
  f.margin = 2.0 * f.measured_excess + 0.5;
  return f;
}

}  // namespace nano::grid
