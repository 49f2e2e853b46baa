#include "bake/mesh/membrane_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "bake/mesh/number_text.hpp"
#include "bake/mesh/mesh_topology_cgal.hpp"

namespace nano::mesh {

namespace {

constexpr double kQuarterTurn = 1.5707963267948966;

std::optional<std::string> remesh_needed(const ProxyMesh& mesh, const MeshReport& report, const RemeshPolicy& policy) {
  if (policy.mode == RemeshPolicy::Mode::off) return std::nullopt;
  if (policy.mode == RemeshPolicy::Mode::edge) return number_text("the scene asks for edges of %.4g Å", policy.edge);
  const std::size_t slivers = std::size_t(std::count_if(report.problems.begin(), report.problems.end(),
                                                        [](const MeshProblem& p) { return p.rule == rule::sliver; }));
  if (slivers > 0) return std::to_string(slivers) + " sliver triangles";
  return remesh_reason(mesh);
}

glm::dvec3 centroid(const ProxyMesh& mesh, std::size_t t) {
  return (mesh.corner_position(t, 0) + mesh.corner_position(t, 1) + mesh.corner_position(t, 2)) / 3.0;
}

}  // namespace

MembraneFit fit_membrane(ProxyMesh& mesh, MeshReport& report, double thickness, const RemeshPolicy& policy) {
  MembraneFit fit;
  const std::optional<std::string> reason = remesh_needed(mesh, report, policy);
  if (reason)
    for (const MeshProblem& p : report.problems)
      if (!is_uv_rule(p.rule) && p.rule != rule::sliver)
        throw std::invalid_argument("cannot remesh a mesh with a " + p.rule +
                                    (p.face >= 0 ? " (face " + std::to_string(p.face) + ")" : std::string()));
  if (!report.closed) return fit;  // check-mesh names what is wrong; nothing here to measure

  // Judged on the user's surface, so the triangles named are the file's.
  const std::vector<double> walls = distances_along_normals(mesh, true);
  const std::vector<double> gaps = distances_along_normals(mesh, false);
  const std::vector<double> creases = reason ? triangle_creases(mesh) : std::vector<double>(mesh.triangles.size(), 0.0);
  fit.thinnest_wall = fit.narrowest_gap = INFINITY;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!(walls[t] > 0.0)) continue;  // degenerate
    fit.thinnest_wall = std::min(fit.thinnest_wall, walls[t]);
    fit.narrowest_gap = std::min(fit.narrowest_gap, gaps[t]);
    const auto tight = [&](const char* what, double found, double needed) {
      fit.tight.push_back({static_cast<std::uint32_t>(t), centroid(mesh, t), what, found, needed, creases[t]});
    };
    // Rounding a crease of angle θ moves the surface in by radius·(1/cos(θ/2) − 1) at best, on both
    // sides of a wall at worst; the smoothing moves it more. Calibrated at 90° (kCreaseWallAt90).
    const double half_turn = 0.5 * std::min(creases[t], 120.0) / kDegreesPerRadian;
    const double rounded_wall =
        thickness * (1.0 + (kCreaseWallAt90 - 1.0) * (1.0 - std::cos(half_turn)) / (1.0 - std::cos(kQuarterTurn / 2.0)));
    if (walls[t] < thickness) tight("wall", walls[t], thickness);
    else if (gaps[t] < thickness) tight("gap", gaps[t], thickness);
    else if (creases[t] > kRemeshCreaseDegrees && walls[t] < rounded_wall) tight("crease", walls[t], rounded_wall);
  }
  std::sort(fit.tight.begin(), fit.tight.end(), [](const TightFeature& a, const TightFeature& b) {
    return a.found / a.needed < b.found / b.needed || (a.found / a.needed == b.found / b.needed && a.triangle < b.triangle);
  });
  for (const TightFeature& f : fit.tight) fit.scale_needed = std::max(fit.scale_needed, f.needed / f.found);
  if (!fit.fits() || !reason) return fit;

  const RemeshOptions options = membrane_remesh_options(
      mesh, thickness, policy.mode == RemeshPolicy::Mode::edge ? std::optional<double>(policy.edge) : std::nullopt);
  fit.remesh = remesh_for_membrane(mesh, options, *reason);
  report = check_mesh(mesh, CheckOptions{});
  return fit;
}

std::string describe_tight_features(const MembraneFit& fit, double thickness, std::optional<double> diameter,
                                    std::size_t shown) {
  std::string text = std::to_string(fit.tight.size()) + number_text(" triangles where a bilayer %.1f Å thick cannot follow the surface", thickness) +
                     ":";
  for (std::size_t i = 0; i < std::min(shown, fit.tight.size()); ++i) {
    const TightFeature& f = fit.tight[i];
    char line[320];
    if (f.what == std::string("wall"))
      std::snprintf(line, sizeof line, "\n  triangle %u at (%.1f, %.1f, %.1f) Å: a wall %.1f Å thick (local radius %.1f Å; the bilayer needs %.1f Å)",
                    f.triangle, f.position.x, f.position.y, f.position.z, f.found, f.found / 2, f.needed);
    else if (f.what == std::string("gap"))
      std::snprintf(line, sizeof line, "\n  triangle %u at (%.1f, %.1f, %.1f) Å: a gap %.1f Å wide (local radius %.1f Å; the bilayer needs %.1f Å)",
                    f.triangle, f.position.x, f.position.y, f.position.z, f.found, f.found / 2, f.needed);
    else
      std::snprintf(line, sizeof line, "\n  triangle %u at (%.1f, %.1f, %.1f) Å: a %.0f° crease on a wall %.1f Å thick (rounding it for the bilayer needs %.1f Å)",
                    f.triangle, f.position.x, f.position.y, f.position.z, f.crease_degrees, f.found, f.needed);
    text += line;
  }
  if (fit.tight.size() > shown) text += "\n  ...";
  if (diameter) text += number_text("\n  the mesh would take the bilayer at \"diameter\": %.0f Å or more", std::ceil(*diameter * fit.scale_needed));
  else text += number_text("\n  the mesh would take the bilayer scaled by %.3g or more (\"scale\")", fit.scale_needed);
  return text;
}

}  // namespace nano::mesh
