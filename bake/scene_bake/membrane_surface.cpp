#include "bake/scene_bake/membrane_surface.hpp"

#include <algorithm>
#include <cmath>

#include "bake/mesh/uv_distortion.hpp"
#include "bake/mesh/vertex_normals.hpp"
#include "common/parallel_for.hpp"

namespace nano::scene_bake {
namespace {

// Candidate tile scales tried per mesh: quantiles of the triangles' smallest stretch by area.
constexpr int kScaleCandidates = 64;
// More than this share of a membrane's copies on checked triangles: checking them all costs little
// more, and the tiles can then be packed rigid, as dense as the patch.
constexpr double kWholeSurfaceShare = 0.5;
// What the corner normals' turn rate misses of the smooth surface's (as the bake always allowed).
constexpr double kTurnRateMargin = 1.05;

bool within_limits(const TriangleDistortion& d, const PackableDistortion& limits) {
  return d.minor > 0.0 && d.major <= limits.stretch * d.minor && d.turn_rate <= limits.turn_rate && d.tilt <= limits.tilt;
}

// The tile scale k whose window [k, stretch·k] of singular values holds the largest area of
// triangles otherwise within the limits (the larger k on a tie: denser tiles); 0 when none.
double best_tile_scale(const std::vector<TriangleDistortion>& triangles, const PackableDistortion& limits) {
  std::vector<std::pair<double, double>> minors;  // (σ2, area) of triangles within the limits
  double total = 0.0;
  for (const TriangleDistortion& d : triangles)
    if (within_limits(d, limits)) {
      minors.emplace_back(d.minor, d.area);
      total += d.area;
    }
  if (minors.empty()) return 0.0;
  std::sort(minors.begin(), minors.end());
  std::vector<double> candidates{minors.front().first};
  double seen = 0.0;
  for (const auto& [minor, area] : minors) {
    seen += area;
    if (seen >= total * double(candidates.size()) / kScaleCandidates && minor > candidates.back()) candidates.push_back(minor);
  }
  double best = 0.0, best_area = -1.0;
  for (const double k : candidates) {
    double covered = 0.0;
    for (const TriangleDistortion& d : triangles)
      if (within_limits(d, limits) && d.minor >= k && d.major <= limits.stretch * k) covered += d.area;
    if (covered >= best_area) {
      best_area = covered;
      best = k;
    }
  }
  return best;
}

// The partial plan of one mesh: triangles outside the best window or beyond the limits are checked.
MeshSurfacePlan partial_plan(const std::vector<TriangleDistortion>& triangles, const PackableDistortion& limits,
                             tiles::SurfaceDistortion& pack_for) {
  MeshSurfacePlan plan;
  plan.checked.assign(triangles.size(), 1);
  const double k = best_tile_scale(triangles, limits);
  double smallest = INFINITY, largest = 0.0;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const TriangleDistortion& d = triangles[t];
    plan.area += d.area;
    if (k > 0.0 && within_limits(d, limits) && d.minor >= k && d.major <= limits.stretch * k) {
      plan.checked[t] = 0;
      smallest = std::min(smallest, d.minor);
      largest = std::max(largest, d.major);
      pack_for.curvature = std::max(pack_for.curvature, static_cast<float>(kTurnRateMargin * d.turn_rate));
      pack_for.tilt = std::max(pack_for.tilt, static_cast<float>(d.tilt));
      pack_for.max_rise = std::max(pack_for.max_rise, static_cast<float>(d.sag));
    } else {
      plan.checked_area += d.area;
    }
  }
  if (std::isfinite(smallest)) {
    plan.tile_scale = smallest;
    pack_for.lateral_stretch = std::max(pack_for.lateral_stretch, static_cast<float>(largest / smallest - 1.0));
  }
  return plan;
}

MembraneSurfacePlan rigid_plan(std::span<const mesh::ProxyMesh* const> meshes, double copies) {
  MembraneSurfacePlan plan;
  plan.copies = plan.checked_copies = copies;
  for (const mesh::ProxyMesh* mesh : meshes) {
    MeshSurfacePlan m;
    m.tile_scale = mesh::uv_scale(*mesh);
    for (std::size_t t = 0; t < mesh->triangles.size(); ++t) m.area += mesh::world_area(*mesh, t);
    m.checked_area = m.area;
    plan.meshes.push_back(std::move(m));
  }
  return plan;
}

}  // namespace

std::vector<TriangleDistortion> triangle_distortions(const mesh::ProxyMesh& mesh, double smooth, int threads) {
  std::vector<TriangleDistortion> out(mesh.triangles.size());
  constexpr std::size_t kChunk = 4096;
  parallel_for((out.size() + kChunk - 1) / kChunk, threads, [&](std::size_t chunk) {
    for (std::size_t t = chunk * kChunk; t < std::min(out.size(), (chunk + 1) * kChunk); ++t) {
      TriangleDistortion& d = out[t];
      if (const std::optional<mesh::UvJacobian> j = mesh::uv_jacobian(mesh, t)) {
        const mesh::SingularValues s = mesh::singular_values(*j);
        d.major = s.major;
        d.minor = s.minor;
      }
      d.turn_rate = mesh::triangle_turn_rate(mesh, t);
      d.tilt = mesh::triangle_smooth_normal_tilt(mesh, t, smooth);
      d.sag = mesh::triangle_facet_sag(mesh, t);
      d.area = mesh::world_area(mesh, t);
    }
  });
  return out;
}

MembraneSurfacePlan plan_membrane_surface(std::span<const mesh::ProxyMesh* const> meshes, double copies_per_a2,
                                          double smooth, double whole_surface_budget, int threads,
                                          const PackableDistortion& limits) {
  double area = 0.0;
  for (const mesh::ProxyMesh* mesh : meshes)
    for (std::size_t t = 0; t < mesh->triangles.size(); ++t) area += mesh::world_area(*mesh, t);
  const double copies = area * copies_per_a2;
  if (copies <= whole_surface_budget) return rigid_plan(meshes, copies);

  MembraneSurfacePlan plan;
  plan.whole_surface = false;
  plan.copies = copies;
  for (const mesh::ProxyMesh* mesh : meshes) {
    plan.meshes.push_back(partial_plan(triangle_distortions(*mesh, smooth, threads), limits, plan.pack_for));
    plan.checked_copies += plan.meshes.back().checked_area * copies_per_a2;
  }
  if (plan.checked_copies > kWholeSurfaceShare * copies) return rigid_plan(meshes, copies);
  return plan;
}

}  // namespace nano::scene_bake
