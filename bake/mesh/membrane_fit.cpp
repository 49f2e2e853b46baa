#include "bake/mesh/membrane_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "bake/mesh/mesh_topology_cgal.hpp"
#include "bake/mesh/number_text.hpp"
#include "bake/mesh/vertex_normals.hpp"

namespace nano::mesh {

namespace {

constexpr double kQuarterTurn = 1.5707963267948966;
// A suggested size is checked a little above the estimate: the remeshing at the larger size rounds
// creases over the same bilayer, a smaller share of the shape.
constexpr double kSizeMargin = 1.03;

}  // namespace

std::optional<std::string> remesh_needed(const ProxyMesh& mesh, const MeshReport& report, const RemeshPolicy& policy) {
  if (policy.mode == RemeshPolicy::Mode::off) return std::nullopt;
  if (policy.mode == RemeshPolicy::Mode::edge) return number_text("the scene asks for edges of %.4g Å", policy.edge);
  const std::size_t slivers = std::size_t(std::count_if(report.problems.begin(), report.problems.end(),
                                                        [](const MeshProblem& p) { return p.rule == rule::sliver; }));
  if (slivers > 0) return std::to_string(slivers) + " sliver triangles";
  return remesh_reason(mesh);
}

namespace {

glm::dvec3 centroid(const ProxyMesh& mesh, std::size_t t) {
  return (mesh.corner_position(t, 0) + mesh.corner_position(t, 1) + mesh.corner_position(t, 2)) / 3.0;
}

// The prepare stage: remeshed for the membrane when it needs it.
std::optional<RemeshReport> prepare(ProxyMesh& mesh, MeshReport& report, double thickness, const RemeshPolicy& policy,
                                    const InputSource& source) {
  const std::optional<std::string> reason = remesh_needed(mesh, report, policy);
  if (!reason) return std::nullopt;
  for (const MeshProblem& p : report.problems)
    if (!is_uv_rule(p.rule) && p.rule != rule::sliver)
      source.fail("cannot remesh a mesh with a " + p.rule + (p.face >= 0 ? " (face " + std::to_string(p.face) + ")" : std::string()));
  const RemeshOptions options = membrane_remesh_options(
      mesh, thickness, policy.mode == RemeshPolicy::Mode::edge ? std::optional<double>(policy.edge) : std::nullopt);
  RemeshReport remeshed = remesh_for_membrane(mesh, options, *reason, source);
  report = check_mesh_surface(mesh, CheckOptions{});  // its UVs are gone: the chart stage makes them
  return remeshed;
}

// What a crease of `degrees` needs behind it to be rounded for the bilayer (kCreaseWallAt90).
double rounded_wall(double degrees, double thickness) {
  // Rounding a crease of angle θ moves the surface in by radius·(1/cos(θ/2) − 1) at best, on both
  // sides of a wall at worst; the smoothing moves it more. Calibrated at 90°.
  const double half_turn = 0.5 * std::min(degrees, 120.0) / kDegreesPerRadian;
  return thickness * (1.0 + (kCreaseWallAt90 - 1.0) * (1.0 - std::cos(half_turn)) / (1.0 - std::cos(kQuarterTurn / 2.0)));
}

// Per triangle of the prepared mesh, what is tight there (found == needed == 0: nothing).
struct TightTriangle {
  const char* what = nullptr;
  double found = 0.0, needed = 0.0, crease = 0.0;
};

// `prepared`: the surface the shells will get, whose creases and bends count (on a user's coarse input
// a triangle's corner normals say little of how its surface bends).
std::vector<TightTriangle> tight_triangles(const ProxyMesh& mesh, const MeshReport& report, double thickness,
                                           bool creases_count, MembraneFit& fit, bool prepared = true) {
  const std::size_t n = mesh.triangles.size();
  std::vector<TightTriangle> tight(n);
  for (const MeshProblem& p : report.problems)
    if (p.rule == rule::self_intersection && p.face >= 0 && std::size_t(p.face) < n)
      tight[std::size_t(p.face)] = {"self-intersection", 0.0, thickness, 0.0};
  const std::vector<double> walls = distances_along_normals(mesh, true);
  const std::vector<double> gaps = distances_along_normals(mesh, false);
  const std::vector<double> creases = creases_count ? triangle_creases(mesh) : std::vector<double>(n, 0.0);
  fit.thinnest_wall = fit.narrowest_gap = INFINITY;
  for (std::size_t t = 0; t < n; ++t) {
    if (!(walls[t] > 0.0) || tight[t].what) continue;  // degenerate, or crossing itself
    fit.thinnest_wall = std::min(fit.thinnest_wall, walls[t]);
    fit.narrowest_gap = std::min(fit.narrowest_gap, gaps[t]);
    const double crease_wall = rounded_wall(creases[t], thickness);
    const double bend = prepared && mesh.has_normals() ? triangle_turn_rate(mesh, t) : 0.0;
    if (walls[t] < thickness) tight[t] = {"wall", walls[t], thickness, creases[t]};
    else if (gaps[t] < thickness) tight[t] = {"gap", gaps[t], thickness, creases[t]};
    // The surface bending tighter than one bilayer thickness: the leaflet on its inner side would
    // have to fold onto itself (the shells then find no prism that holds it).
    else if (bend * kMinBendBilayers * thickness > 1.0) tight[t] = {"bend", 1.0 / bend, kMinBendBilayers * thickness, creases[t]};
    else if (creases[t] > kRemeshCreaseDegrees && walls[t] < crease_wall) tight[t] = {"crease", walls[t], crease_wall, creases[t]};
  }
  return tight;
}

// Tight triangles sharing a vertex form one place, described by its tightest triangle.
std::vector<TightFeature> places(const ProxyMesh& mesh, const std::vector<TightTriangle>& tight) {
  std::vector<std::uint32_t> parent(mesh.positions.size());
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](std::uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (std::size_t t = 0; t < tight.size(); ++t)
    if (tight[t].what)
      for (int c = 1; c < 3; ++c) parent[find(mesh.triangles[t][c])] = find(mesh.triangles[t][0]);
  std::vector<std::int64_t> place_of_root(mesh.positions.size(), -1);
  std::vector<TightFeature> out;
  for (std::size_t t = 0; t < tight.size(); ++t) {
    const TightTriangle& tt = tight[t];
    if (!tt.what) continue;
    std::int64_t& place = place_of_root[find(mesh.triangles[t][0])];
    if (place < 0) {
      place = std::int64_t(out.size());
      out.push_back({});
    }
    TightFeature& f = out[std::size_t(place)];
    const TightFeature candidate{centroid(mesh, t), tt.what, tt.found, tt.needed, tt.crease, 0, false};
    if (f.triangles == 0 || candidate.growth() > f.growth()) {
      const std::size_t count = f.triangles;
      f = candidate;
      f.triangles = count;
    }
    ++f.triangles;
  }
  for (TightFeature& f : out) f.defect = !(f.growth() <= kPlausibleGrowth);
  std::sort(out.begin(), out.end(), [](const TightFeature& a, const TightFeature& b) {
    if (a.defect != b.defect) return a.defect;
    if (a.growth() != b.growth()) return a.growth() > b.growth();
    return a.triangles > b.triangles;
  });
  return out;
}

// Where the remeshed surface crosses itself, the input had two sheets (or a wall's two sides) closer
// than the remeshing moves it: the place is described by the input's narrowest gap or wall near it,
// which needs to be as wide as the remeshing may move both sides.
void explain_crossings(const ProxyMesh& input, const RemeshReport& remesh, std::vector<TightFeature>& tight) {
  const double edge = remesh.edge;
  if (std::none_of(tight.begin(), tight.end(), [](const TightFeature& f) { return f.what == "self-intersection"; })) return;
  const std::vector<double> walls = distances_along_normals(input, true), gaps = distances_along_normals(input, false);
  for (TightFeature& f : tight) {
    if (f.what != "self-intersection") continue;
    const double near = 2.0 * edge;
    for (std::size_t t = 0; t < input.triangles.size(); ++t) {
      if (glm::length(centroid(input, t) - f.position) > near) continue;
      for (const auto& [what, found] : {std::pair<const char*, double>{"gap", gaps[t]}, {"wall", walls[t]}})
        if (found > 0.0 && (!f.crossed_when_remeshed || found < f.found)) {
          f.what = what;
          f.found = found;
          f.crossed_when_remeshed = true;
        }
    }
    if (f.crossed_when_remeshed) f.needed = std::max(f.needed, 2.0 * remesh.distance_bound);
    f.defect = !(f.growth() <= kPlausibleGrowth);
  }
}

// The prepare and judge stages once, at the mesh's size (`input`: the mesh before them).
MembraneFit prepare_and_judge(const ProxyMesh& input, ProxyMesh& mesh, MeshReport& report, double thickness,
                              const RemeshPolicy& policy, const InputSource& source) {
  MembraneFit fit;
  fit.remesh = prepare(mesh, report, thickness, policy, source);
  if (!report.closed) return fit;  // check-mesh names what is wrong; nothing here to measure
  // A remeshed surface has rounded what it could: a crease left sharper than the shells follow counts.
  fit.tight = places(mesh, tight_triangles(mesh, report, thickness, fit.remesh.has_value(), fit));
  if (fit.remesh) explain_crossings(input, *fit.remesh, fit.tight);
  // The rounding's toll on the whole shape: what it takes shrinks as the mesh grows against the bilayer.
  // A surface rounded away that much no longer shows why (what it shows is the rounding's damage):
  // the input's own walls and gaps do.
  if (fit.remesh && fit.remesh->area_in > 0.0) {
    const double loss = 1.0 - fit.remesh->area_out / fit.remesh->area_in;
    if (loss > kMaxRoundingAreaLoss) {
      TightFeature whole{glm::dvec3(0.0), "rounding", kMaxRoundingAreaLoss, loss, 0.0, mesh.triangles.size(), false};
      for (const glm::dvec3& p : mesh.positions) whole.position += p / double(mesh.positions.size());
      whole.defect = !(whole.growth() <= kPlausibleGrowth);
      MembraneFit on_input;
      const std::vector<TightFeature> input_places =
          places(input, tight_triangles(input, MeshReport{}, thickness, false, on_input, /*prepared=*/false));
      fit.tight = input_places;  // what the prepared surface shows there is the rounding's own damage
      fit.tight.insert(fit.tight.begin(), whole);
    }
  }
  std::stable_sort(fit.tight.begin(), fit.tight.end(), [](const TightFeature& a, const TightFeature& b) { return a.defect > b.defect; });
  for (const TightFeature& f : fit.tight)
    if (!f.defect) fit.scale_needed = std::max(fit.scale_needed, f.growth());
  return fit;
}

// The smallest scale (from fit.scale_needed up) at which a copy of `input` prepared and judged again
// takes the bilayer; records it in `fit` when one of kSizeChecks rounds finds it.
void check_size(const ProxyMesh& input, double thickness, const RemeshPolicy& policy, const InputSource& source,
                MembraneFit& fit) {
  double scale = fit.scale_needed * kSizeMargin;
  for (int round = 0; round < kSizeChecks && scale <= kPlausibleGrowth; ++round) {
    fit.largest_scale_tried = scale;
    ProxyMesh larger = input;
    for (glm::dvec3& p : larger.positions) p *= scale;
    MeshReport report = check_mesh_surface(larger, CheckOptions{});
    const ProxyMesh larger_input = larger;
    const MembraneFit again = prepare_and_judge(larger_input, larger, report, thickness, policy, source);
    if (again.fits()) {
      fit.scale_needed = scale;
      fit.size_checked = true;
      return;
    }
    if (again.has_defect()) return;
    scale *= again.scale_needed * kSizeMargin;
  }
}

}  // namespace

bool MembraneFit::has_defect() const {
  return std::any_of(tight.begin(), tight.end(), [](const TightFeature& f) { return f.defect; });
}

MembraneFit fit_membrane(ProxyMesh& mesh, MeshReport& report, double thickness, const RemeshPolicy& policy,
                         const InputSource& source) {
  const ProxyMesh input = mesh;
  MembraneFit fit = prepare_and_judge(input, mesh, report, thickness, policy, source);
  if (!fit.fits() && !fit.has_defect()) check_size(input, thickness, policy, source, fit);
  return fit;
}

namespace {

std::string place_text(const TightFeature& f, double file_scale) {
  if (f.what == "rounding") return "the whole mesh";
  char line[200];
  std::snprintf(line, sizeof line, "at (%.1f, %.1f, %.1f) Å", f.position.x, f.position.y, f.position.z);
  std::string text = line;
  if (file_scale != 1.0 && file_scale > 0.0) {
    const glm::dvec3 p = f.position / file_scale;
    std::snprintf(line, sizeof line, " (%.6g, %.6g, %.6g) in the file's coordinates", p.x, p.y, p.z);
    text += line;
  }
  return text + " (" + std::to_string(f.triangles) + (f.triangles == 1 ? " triangle)" : " triangles)");
}

std::string feature_text(const TightFeature& f, double thickness) {
  const std::string what = f.what;
  if (what == "self-intersection") return "the surface passes through itself";
  if (what == "rounding")
    return number_text("rounding its creases for the bilayer takes %.0f %% of its area", 100.0 * f.needed) +
           number_text(" (at most %.0f %%): the mesh is too small for creases this sharp", 100.0 * f.found);
  char line[240];
  if (f.crossed_when_remeshed) {
    std::snprintf(line, sizeof line, "%s %.1f Å %s (remeshed for the bilayer, the surface crosses itself there; %.1f Å would do)",
                  what == "gap" ? "two sheets of the surface come within" : "a wall", f.found, what == "gap" ? "of each other" : "thick",
                  f.needed);
    return line;
  }
  if (what == "wall")
    std::snprintf(line, sizeof line, "a wall %.1f Å thick (the bilayer needs %.1f Å)", f.found, f.needed);
  else if (what == "gap")
    std::snprintf(line, sizeof line, "%s %.1f Å wide (the bilayer needs %.1f Å)",
                  f.found < 0.25 * thickness ? "two sheets of the surface nearly touch: a gap" : "a gap", f.found, f.needed);
  else if (what == "bend")
    std::snprintf(line, sizeof line, "the surface bends with a radius of %.1f Å (the bilayer needs %.1f Å)", f.found, f.needed);
  else
    std::snprintf(line, sizeof line, "a %.0f° crease on a wall %.1f Å thick (rounding it for the bilayer needs %.1f Å)",
                  f.crease_degrees, f.found, f.needed);
  return line;
}

std::string defect_advice(const TightFeature& f) {
  const std::string what = f.what;
  if (what == "gap" || what == "self-intersection")
    return ": a defect of the mesh no plausible size cures (move those parts apart or join them in the mesh)";
  return number_text(": a defect of the mesh no plausible size cures (only %.3g times this size would; thicken or remove that part)",
                     f.growth());
}

}  // namespace

std::string describe_tight_features(const MembraneFit& fit, double thickness, std::optional<double> diameter,
                                    double file_scale, std::size_t shown) {
  std::string text = std::to_string(fit.tight.size()) + (fit.tight.size() == 1 ? " place" : " places") +
                     number_text(" where a bilayer %.1f Å thick cannot follow the surface", thickness) + ":";
  for (std::size_t i = 0; i < std::min(shown, fit.tight.size()); ++i) {
    const TightFeature& f = fit.tight[i];
    text += "\n  " + place_text(f, file_scale) + ": " + feature_text(f, thickness) + (f.defect ? defect_advice(f) : "");
  }
  if (fit.tight.size() > shown) text += "\n  ...";
  if (fit.has_defect()) return text + "\n  mend the mesh at the places named a defect; no diameter is given while they remain";
  if (!fit.size_checked) {
    // Prepared and judged again at larger sizes, it still did not fit: no size within reason is named.
    const std::string tried = diameter ? number_text("\"diameter\": %.0f Å", std::ceil(*diameter * fit.largest_scale_tried))
                                       : number_text("%.3g times the size", fit.largest_scale_tried);
    return text + "\n  prepared and judged again at up to " + tried +
           ", it still does not take the bilayer: mend the mesh at the places named";
  }
  const std::string size = diameter ? number_text("at \"diameter\": %.0f Å or more", std::ceil(*diameter * fit.scale_needed))
                                    : number_text("scaled by %.3g or more (\"scale\")", fit.scale_needed);
  return text + "\n  the mesh would take the bilayer " + size + " (checked: at that size it fits)";
}

}  // namespace nano::mesh
