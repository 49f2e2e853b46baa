#include "bake/mesh/mesh_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <numeric>

#include <glm/geometric.hpp>

#include "bake/mesh/mesh_edges.hpp"
#include "bake/mesh/mesh_topology_cgal.hpp"
#include "bake/mesh/uv_distortion.hpp"

namespace nano::mesh {

bool is_uv_rule(const std::string& rule) {
  return rule == rule::no_uvs || rule == rule::uv_outside || rule == rule::zero_area_uv || rule == rule::flipped_uv;
}


namespace {

double edge_length(const ProxyMesh& mesh, const MeshEdge& edge) {
  return glm::length(mesh.positions[edge.b] - mesh.positions[edge.a]);
}

std::string edge_name(const MeshEdge& edge) {
  return "edge between vertices " + std::to_string(edge.a) + " and " + std::to_string(edge.b);
}

double min_angle_degrees(const ProxyMesh& mesh, std::size_t t) {
  double smallest = 180.0;
  for (int c = 0; c < 3; ++c) {
    const glm::dvec3 p = mesh.corner_position(t, c);
    const glm::dvec3 e1 = mesh.corner_position(t, (c + 1) % 3) - p, e2 = mesh.corner_position(t, (c + 2) % 3) - p;
    const double angle = std::atan2(glm::length(glm::cross(e1, e2)), glm::dot(e1, e2));
    smallest = std::min(smallest, angle * 180.0 / std::numbers::pi);
  }
  return smallest;
}

// Connected runs of border edges (joined at shared vertices): the holes of the surface.
std::size_t count_holes(const ProxyMesh& mesh, const std::vector<MeshEdge>& edges) {
  std::vector<std::uint32_t> parent(mesh.positions.size());
  std::iota(parent.begin(), parent.end(), 0u);
  const auto root = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<bool> on_border(mesh.positions.size(), false);
  for (const MeshEdge& edge : edges) {
    if (edge.uses.size() != 1) continue;
    on_border[edge.a] = on_border[edge.b] = true;
    parent[root(edge.a)] = root(edge.b);
  }
  std::size_t loops = 0;
  for (std::uint32_t v = 0; v < parent.size(); ++v) loops += on_border[v] && root(v) == v;
  return loops;
}

void check_topology(const ProxyMesh& mesh, const std::vector<MeshEdge>& edges, MeshReport& report) {
  bool border = false, non_manifold = false, inconsistent = false;
  for (const MeshEdge& edge : edges) {
    if (edge.uses.size() == 1) {
      border = true;
      report.problems.push_back({edge.uses[0].face, rule::border_edge, edge_length(mesh, edge), edge_name(edge)});
    } else if (edge.uses.size() > 2) {
      non_manifold = true;
      for (const EdgeUse& use : edge.uses)
        report.problems.push_back({use.face, rule::non_manifold_edge, static_cast<double>(edge.uses.size()),
                                   edge_name(edge) + " has " + std::to_string(edge.uses.size()) + " faces"});
    } else if (edge.uses[0].forward == edge.uses[1].forward) {
      inconsistent = true;
      const EdgeUse& later = edge.uses[0].face > edge.uses[1].face ? edge.uses[0] : edge.uses[1];
      const EdgeUse& earlier = &later == &edge.uses[0] ? edge.uses[1] : edge.uses[0];
      report.problems.push_back({later.face, rule::inconsistent_orientation, static_cast<double>(earlier.face),
                                 edge_name(edge) + " runs the same way in face " + std::to_string(earlier.face)});
    }
  }
  report.holes = count_holes(mesh, edges);
  if (report.holes > 0) {
    std::size_t border_edges = 0;
    for (const MeshEdge& edge : edges) border_edges += edge.uses.size() == 1;
    report.problems.push_back({-1, rule::holes, static_cast<double>(report.holes),
                               std::to_string(report.holes) + " boundary loop(s) of " + std::to_string(border_edges) +
                                   " border edges: the surface is open"});
  }
  const auto vertices = non_manifold_vertices(mesh, edges);
  for (const NonManifoldVertex& v : vertices)
    report.problems.push_back({v.first_face, rule::non_manifold_vertex, static_cast<double>(v.fans),
                               "vertex " + std::to_string(v.vertex) + " joins " + std::to_string(v.fans) + " fans"});
  report.closed = !border;
  report.manifold = !non_manifold && vertices.empty();
  report.oriented = !inconsistent;
}

// Returns true when some triangle is degenerate (CGAL's intersection test must then be skipped).
bool check_triangle_shapes(const ProxyMesh& mesh, const CheckOptions& options, MeshReport& report) {
  bool degenerate = false;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    const auto face = static_cast<std::int64_t>(t);
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
      degenerate = true;
      report.problems.push_back({face, rule::repeated_vertex, 0.0, "a vertex index appears twice"});
    } else if (exactly_collinear(mesh.corner_position(t, 0), mesh.corner_position(t, 1), mesh.corner_position(t, 2))) {
      degenerate = true;
      report.problems.push_back({face, rule::zero_area, world_area(mesh, t), "the three corners are collinear"});
    } else if (const double angle = min_angle_degrees(mesh, t); angle < options.min_angle_degrees) {
      char detail[96];
      std::snprintf(detail, sizeof detail, "smallest angle %.4g deg < %.4g deg", angle, options.min_angle_degrees);
      report.problems.push_back({face, rule::sliver, angle, detail});
    }
  }
  return degenerate;
}

void check_solid(const ProxyMesh& mesh, bool degenerate, MeshReport& report) {
  const SolidProperties solid = analyse_solid(mesh, !degenerate);
  report.volume = solid.volume;
  if (solid.polygon_mesh) {
    report.area = solid.area;
  } else {
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) report.area += world_area(mesh, t);
    // The exact edge checks above explain why in every case we know of; this catches the rest.
    if (report.closed && report.manifold && report.oriented && !degenerate)
      report.problems.push_back({-1, rule::not_polygon_mesh, 0.0, "CGAL cannot build a surface mesh from the faces"});
  }
  report.outward = solid.outward && solid.volume.value_or(0.0) > 0.0;
  if (solid.closed && !report.outward)
    report.problems.push_back({-1, rule::inward_orientation, solid.volume.value_or(0.0),
                               "faces run clockwise seen from outside (negative signed volume)"});
  for (const auto& [f, g] : solid.self_intersections)
    report.problems.push_back({f, rule::self_intersection, static_cast<double>(g), "intersects face " + std::to_string(g)});
}

void check_uv_range_and_orientation(const ProxyMesh& mesh, const std::vector<MeshEdge>& edges, MeshReport& report) {
  const std::vector<std::uint32_t> chart = uv_charts(mesh, edges);
  report.uv_charts = chart.empty() ? 0 : *std::max_element(chart.begin(), chart.end()) + 1;
  std::vector<int> orientation(mesh.triangles.size());
  std::vector<double> ccw_area(report.uv_charts, 0.0), cw_area(report.uv_charts, 0.0);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto face = static_cast<std::int64_t>(t);
    double outside = 0.0;
    for (int c = 0; c < 3; ++c) {
      const glm::dvec2 uv = mesh.corner_uv(t, c);
      outside = std::max({outside, -uv.x, uv.x - 1.0, -uv.y, uv.y - 1.0});
    }
    if (outside > 0.0 || std::isnan(outside))
      report.problems.push_back({face, rule::uv_outside, outside, "a corner's UV lies outside the unit square"});
    orientation[t] = exact_orientation_2d(mesh.corner_uv(t, 0), mesh.corner_uv(t, 1), mesh.corner_uv(t, 2));
    if (orientation[t] == 0)
      report.problems.push_back({face, rule::zero_area_uv, uv_signed_area(mesh, t), "the three UVs are collinear"});
    (orientation[t] > 0 ? ccw_area : cw_area)[chart[t]] += orientation[t] != 0 ? world_area(mesh, t) : 0.0;
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (orientation[t] == 0) continue;
    const int majority = ccw_area[chart[t]] >= cw_area[chart[t]] ? 1 : -1;
    if (majority < 0) ++report.mirrored_triangles;
    if (orientation[t] != majority)
      report.problems.push_back({static_cast<std::int64_t>(t), rule::flipped_uv, uv_signed_area(mesh, t),
                                 "UV winding is opposite to the rest of UV chart " + std::to_string(chart[t])});
  }
}

void measure_seams(const ProxyMesh& mesh, const std::vector<MeshEdge>& edges, MeshReport& report) {
  for (const MeshEdge& edge : edges) {
    if (!is_seam(mesh, edge)) continue;
    ++report.seam_edges;
    report.seam_length += edge_length(mesh, edge);
  }
}

void measure_distortion(const ProxyMesh& mesh, const CheckOptions& options, MeshReport& report) {
  report.uv_scale_k = uv_scale(mesh);
  if (!(report.uv_scale_k > 0.0)) return;
  std::vector<TriangleDistortion> all;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto j = uv_jacobian(mesh, t);
    if (!j) continue;
    const SingularValues sv = singular_values(*j);
    if (!(sv.minor > 0.0)) continue;  // degenerate in 3D: reported as a problem already
    all.push_back({static_cast<std::uint32_t>(t), sv.major / report.uv_scale_k, sv.minor / report.uv_scale_k});
  }
  if (all.empty()) return;
  report.sigma_min = report.sigma_max = all.front().sigma2;
  for (const TriangleDistortion& d : all) {
    report.sigma_min = std::min(report.sigma_min, d.sigma2);
    report.sigma_max = std::max(report.sigma_max, d.sigma1);
  }
  auto badness = [](const TriangleDistortion& d) { return std::max(d.sigma1, 1.0 / d.sigma2); };
  const std::size_t n = std::min(options.worst_count, all.size());
  std::partial_sort(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(n), all.end(),
                    [&](const auto& x, const auto& y) { return badness(x) > badness(y); });
  report.worst.assign(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(n));
}

void measure_replication_area(const ProxyMesh& mesh, const CheckOptions& options, MeshReport& report) {
  if (!(report.uv_scale_k > 0.0)) return;
  report.tile_size_world = options.tile_size.value_or(report.uv_scale_k / 20.0);
  report.tile_size_uv = report.tile_size_world / report.uv_scale_k;
  report.replication_area = replication_area(mesh, report.tile_size_uv);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto span = triangle_tile_span(mesh, t, report.tile_size_uv);
    if (span[0] < report.replication_area[0] && span[1] < report.replication_area[1]) continue;
    const glm::dvec2 a = mesh.corner_uv(t, 0), b = mesh.corner_uv(t, 1), c = mesh.corner_uv(t, 2);
    const glm::dvec2 box = glm::max(a, glm::max(b, c)) - glm::min(a, glm::min(b, c));
    const double area = std::abs(uv_signed_area(mesh, t));
    const double elongation = area > 0.0 ? std::pow(std::max(box.x, box.y), 2) / (2.0 * area) : INFINITY;
    if (elongation > options.thin_uv_elongation)
      report.warnings.push_back({static_cast<std::int64_t>(t), rule::thin_uv, elongation,
                                 "needs " + std::to_string(span[0]) + "x" + std::to_string(span[1]) + " tiles"});
  }
}

}  // namespace

namespace {

void check_surface(const ProxyMesh& mesh, const std::vector<MeshEdge>& edges, const CheckOptions& options, MeshReport& report) {
  report.triangles = mesh.triangles.size();
  report.vertices = mesh.positions.size();
  if (mesh.triangles.size() > options.max_triangles)
    report.problems.push_back({-1, rule::too_many_triangles, static_cast<double>(mesh.triangles.size()),
                               "more than " + std::to_string(options.max_triangles) +
                                   " triangles: a proxy mesh is low-poly (its triangles become prisms of molecules)"});
  check_topology(mesh, edges, report);
  const bool degenerate = check_triangle_shapes(mesh, options, report);
  check_solid(mesh, degenerate, report);
}

void sort_problems(MeshReport& report) {
  std::stable_sort(report.problems.begin(), report.problems.end(),
                   [](const MeshProblem& a, const MeshProblem& b) { return a.face < b.face; });
}

}  // namespace

MeshReport check_mesh_surface(const ProxyMesh& mesh, const CheckOptions& options) {
  MeshReport report;
  check_surface(mesh, collect_edges(mesh), options, report);
  sort_problems(report);
  return report;
}

MeshReport check_mesh(const ProxyMesh& mesh, const CheckOptions& options) {
  MeshReport report;
  const std::vector<MeshEdge> edges = collect_edges(mesh);
  check_surface(mesh, edges, options, report);
  report.has_uvs = mesh.has_uvs();
  if (!report.has_uvs) {
    report.problems.push_back({-1, rule::no_uvs, 0.0, "the mesh has no texture coordinates"});
  } else {
    check_uv_range_and_orientation(mesh, edges, report);
    measure_seams(mesh, edges, report);
    measure_distortion(mesh, options, report);
    measure_replication_area(mesh, options, report);
  }
  sort_problems(report);
  return report;
}

nlohmann::json report_to_json(const MeshReport& r) {
  using nlohmann::json;
  auto problem_list = [](const std::vector<MeshProblem>& list) {
    json out = json::array();
    for (const MeshProblem& p : list)
      out.push_back({{"face", p.face}, {"rule", p.rule}, {"value", p.value}, {"detail", p.detail}});
    return out;
  };
  json j = {{"usable", r.usable()},  {"triangles", r.triangles}, {"vertices", r.vertices},
            {"closed", r.closed},    {"manifold", r.manifold},   {"oriented", r.oriented},
            {"outward", r.outward},  {"holes", r.holes},       {"problems", problem_list(r.problems)},
            {"warnings", problem_list(r.warnings)}, {"area", r.area}};
  j["volume"] = r.volume ? json(*r.volume) : json(nullptr);
  if (!r.has_uvs) {
    for (const char* key : {"seams", "distortion", "uv_scale_k", "tile_size", "replication_area", "uv_charts"})
      j[key] = nullptr;
    return j;
  }
  json worst = json::array();
  for (const TriangleDistortion& d : r.worst) worst.push_back({{"face", d.face}, {"sigma1", d.sigma1}, {"sigma2", d.sigma2}});
  j["seams"] = {{"edges", r.seam_edges}, {"length", r.seam_length}};
  j["distortion"] = {{"sigma_min", r.sigma_min}, {"sigma_max", r.sigma_max}, {"worst", worst}};
  j["uv_scale_k"] = r.uv_scale_k;
  j["tile_size"] = {{"world", r.tile_size_world}, {"uv", r.tile_size_uv}};
  j["replication_area"] = {r.replication_area[0], r.replication_area[1]};
  j["uv_charts"] = r.uv_charts;
  j["mirrored_triangles"] = r.mirrored_triangles;
  return j;
}

std::string report_to_text(const MeshReport& r, const std::string& file) {
  std::string out;
  char line[512];
  auto yes_no = [](bool b) { return b ? "yes" : "no"; };
  std::snprintf(line, sizeof line, "%s: %zu triangles, %zu vertices; closed %s, manifold %s, oriented %s, outward %s\n",
                file.c_str(), r.triangles, r.vertices, yes_no(r.closed), yes_no(r.manifold), yes_no(r.oriented),
                yes_no(r.outward));
  out += line;
  std::snprintf(line, sizeof line, "  area %.6g, volume %s\n", r.area,
                r.volume ? std::to_string(*r.volume).c_str() : "n/a (not closed)");
  out += line;
  if (r.has_uvs) {
    std::snprintf(line, sizeof line,
                  "  UV: %zu charts (%zu mirrored triangles), %zu seam edges of total length %.6g\n"
                  "  UV scale k = %.6g world units per UV unit; distortion sigma in [%.4f, %.4f]\n"
                  "  tile size S = %.6g (s = %.6g in UV) -> replication area %d x %d\n",
                  r.uv_charts, r.mirrored_triangles, r.seam_edges, r.seam_length, r.uv_scale_k, r.sigma_min,
                  r.sigma_max, r.tile_size_world, r.tile_size_uv, r.replication_area[0], r.replication_area[1]);
    out += line;
    for (const TriangleDistortion& d : r.worst) {
      std::snprintf(line, sizeof line, "    face %u: sigma1 %.4f, sigma2 %.4f\n", d.face, d.sigma1, d.sigma2);
      out += line;
    }
  }
  auto list = [&](const std::vector<MeshProblem>& problems, const char* label) {
    for (const MeshProblem& p : problems) {
      const std::string where = p.face >= 0 ? "face " + std::to_string(p.face) : "mesh";
      std::snprintf(line, sizeof line, "%s%s:%s: %s (value %.6g; %s)\n", label, file.c_str(), where.c_str(),
                    p.rule.c_str(), p.value, p.detail.c_str());
      out += line;
    }
  };
  list(r.warnings, "warning: ");
  list(r.problems, "");
  out += r.usable() ? "usable\n" : "NOT usable: " + std::to_string(r.problems.size()) + " problem(s)\n";
  return out;
}

}  // namespace nano::mesh
