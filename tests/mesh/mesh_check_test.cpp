// check-mesh on hand-built meshes with planted defects: each must be named with its face and rule.
#include <algorithm>

#include <gtest/gtest.h>

#include "bake/mesh/mesh_check.hpp"
#include "bake/mesh/mesh_edges.hpp"
#include "bake/mesh/mesh_reader.hpp"
#include "bake/mesh/mesh_topology_cgal.hpp"
#include "tests/mesh/test_obj.hpp"

namespace nano::mesh {
namespace {

using testing::octahedron_faces;
using testing::octahedron_uvs;
using testing::octahedron_vertices;
using testing::TempDir;

MeshReport check_text(const std::string& obj) {
  TempDir dir;
  return check_mesh(read_proxy_mesh(dir.write("m.obj", obj)), CheckOptions{});
}

bool has_problem(const MeshReport& r, std::int64_t face, const std::string& rule) {
  return std::any_of(r.problems.begin(), r.problems.end(),
                     [&](const MeshProblem& p) { return p.face == face && p.rule == rule; });
}

std::vector<std::int64_t> faces_with(const MeshReport& r, const std::string& rule) {
  std::vector<std::int64_t> faces;
  for (const MeshProblem& p : r.problems)
    if (p.rule == rule) faces.push_back(p.face);
  return faces;
}

std::string replace_line(std::string text, const std::string& line, const std::string& replacement) {
  const auto at = text.find(line);
  EXPECT_NE(at, std::string::npos) << line;
  return text.replace(at, line.size(), replacement);
}

TEST(CheckMesh, OctahedronIsUsable) {
  const MeshReport r = check_text(testing::octahedron);
  EXPECT_TRUE(r.usable()) << report_to_text(r, "octa");
  EXPECT_TRUE(r.closed && r.manifold && r.oriented && r.outward);
  EXPECT_EQ(r.triangles, 8u);
  EXPECT_EQ(r.vertices, 6u);
  EXPECT_EQ(r.seam_edges, 4u);                          // the four edges to −Z
  EXPECT_NEAR(r.seam_length, 4 * std::sqrt(2.0), 1e-6);
  EXPECT_EQ(r.uv_charts, 1u);
  EXPECT_NEAR(r.area, 8 * std::sqrt(3.0) / 2, 1e-6);    // 8 equilateral triangles of side √2
  ASSERT_TRUE(r.volume);
  EXPECT_NEAR(*r.volume, 4.0 / 3.0, 1e-6);              // |x|+|y|+|z| ≤ 1
  // Every face: world area √3/2, UV area 1/8 → k = √(4√3); each UV triangle is a right
  // isosceles triangle onto an equilateral one, with the same σ for all faces.
  EXPECT_NEAR(r.uv_scale_k, std::sqrt(4 * std::sqrt(3.0)), 1e-6);
  EXPECT_NEAR(r.sigma_max * r.sigma_min, 1.0, 1e-6);    // area preserving after normalisation by k
  // Default tile: s = 1/20; UV boxes are 0.5 × 0.5 → ceil(10) + 1 = 11.
  EXPECT_NEAR(r.tile_size_uv, 0.05, 1e-12);
  EXPECT_EQ(r.replication_area, (std::array<int, 2>{11, 11}));
}

TEST(CheckMesh, TileSizeInWorldUnitsSetsReplicationArea) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write("m.obj", testing::octahedron));
  CheckOptions options;
  const double k = std::sqrt(4 * std::sqrt(3.0));
  options.tile_size = k * 0.125;  // s = 1/8 → 0.5 / 0.125 = 4 tiles + 1
  EXPECT_EQ(check_mesh(mesh, options).replication_area, (std::array<int, 2>{5, 5}));
}

TEST(CheckMesh, NoUvs) {
  const MeshReport r = check_text(octahedron_vertices + "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 2 1 6\nf 3 2 6\nf 4 3 6\nf 1 4 6\n");
  EXPECT_FALSE(r.usable());
  EXPECT_EQ(faces_with(r, rule::no_uvs), (std::vector<std::int64_t>{-1}));
  EXPECT_TRUE(r.closed && r.manifold && r.oriented && r.outward);
  EXPECT_EQ(report_to_json(r)["replication_area"], nullptr);
}

TEST(CheckMesh, UvOutsideUnitSquare) {
  const MeshReport r = check_text(octahedron_vertices + octahedron_uvs + "vt 0.5 1.25\n" +
                                  replace_line(octahedron_faces, "f 1/1 2/2 5/5", "f 1/1 2/10 5/5"));
  EXPECT_EQ(faces_with(r, rule::uv_outside), (std::vector<std::int64_t>{0}));
  EXPECT_NEAR(r.problems.front().value, 0.25, 1e-7);
  EXPECT_EQ(r.problems.size(), 1u) << report_to_text(r, "m");
}

TEST(CheckMesh, ZeroAreaUvTriangle) {
  // (1, .5), (.5, 1), (.75, .75): the third UV is the midpoint of the first two.
  const MeshReport r = check_text(octahedron_vertices + octahedron_uvs + "vt 0.75 0.75\n" +
                                  replace_line(octahedron_faces, "f 1/1 2/2 5/5", "f 1/1 2/2 5/10"));
  EXPECT_EQ(faces_with(r, rule::zero_area_uv), (std::vector<std::int64_t>{0}));
  EXPECT_EQ(r.problems.size(), 1u) << report_to_text(r, "m");
}

TEST(CheckMesh, FlippedUvTriangle) {
  // Moving face 0's +Z corner to (.9, .9) folds it over its UV edge (1,.5)–(.5,1); the face
  // stays in the chart through that (non-seam) edge, whose majority winds counter-clockwise.
  const MeshReport r = check_text(octahedron_vertices + octahedron_uvs + "vt 0.9 0.9\n" +
                                  replace_line(octahedron_faces, "f 1/1 2/2 5/5", "f 1/1 2/2 5/10"));
  EXPECT_EQ(faces_with(r, rule::flipped_uv), (std::vector<std::int64_t>{0}));
  EXPECT_LT(r.problems.front().value, 0.0);
  EXPECT_EQ(r.problems.size(), 1u) << report_to_text(r, "m");
}

TEST(CheckMesh, WholeMirroredChartIsNotFlipped) {
  // Mirror every UV (u → 1 − u): the single chart now winds clockwise everywhere, which the
  // tile mapper handles by flipping the bitangent.
  const MeshReport r = check_text(octahedron_vertices +
                                  "vt 0 0.5\nvt 0.5 1\nvt 1 0.5\nvt 0.5 0\nvt 0.5 0.5\nvt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\n" +
                                  octahedron_faces);
  EXPECT_TRUE(r.usable()) << report_to_text(r, "m");
  EXPECT_EQ(r.mirrored_triangles, 8u);
}

TEST(CheckMesh, NonManifoldEdge) {
  // A ninth face on edge 1–2 (already shared by faces 0 and 4).
  const MeshReport r = check_text(octahedron_vertices + "v 1 1 1\n" + octahedron_uvs + "vt 0.9 0.9\n" +
                                  octahedron_faces + "f 1/1 2/2 7/10\n");
  EXPECT_EQ(faces_with(r, rule::non_manifold_edge), (std::vector<std::int64_t>{0, 4, 8}));
  for (const MeshProblem& p : r.problems)
    if (p.rule == rule::non_manifold_edge) {
      EXPECT_EQ(p.value, 3.0);
    }
  EXPECT_FALSE(r.manifold);
  EXPECT_TRUE(has_problem(r, 8, rule::border_edge));  // its two free edges
}

TEST(CheckMesh, NonManifoldVertex) {
  // Two octahedra touching at one point: +X of the first is −X of the second (welded on load).
  const MeshReport r = check_text(octahedron_vertices + "v 3 0 0\nv 2 1 0\nv 1 0 0\nv 2 -1 0\nv 2 0 1\nv 2 0 -1\n" +
                                  octahedron_uvs + octahedron_faces +
                                  "f 7/1 8/2 11/5\nf 8/2 9/3 11/5\nf 9/3 10/4 11/5\nf 10/4 7/1 11/5\n"
                                  "f 8/2 7/1 12/6\nf 9/3 8/2 12/7\nf 10/4 9/3 12/8\nf 7/1 10/4 12/9\n");
  EXPECT_EQ(r.vertices, 11u);
  EXPECT_EQ(faces_with(r, rule::non_manifold_vertex), (std::vector<std::int64_t>{0}));
  EXPECT_FALSE(r.manifold);
  EXPECT_TRUE(r.closed);
}

TEST(CheckMesh, ZeroAreaTriangle) {
  // Face 8 has a corner on the midpoint of edge 1–2; the edges it adds are border and
  // non-manifold side effects, the degenerate shape is its own rule.
  const MeshReport r = check_text(octahedron_vertices + "v 0.5 0.5 0\n" + octahedron_uvs + "vt 0.9 0.9\n" +
                                  octahedron_faces + "f 1/1 2/2 7/10\n");
  EXPECT_EQ(faces_with(r, rule::zero_area), (std::vector<std::int64_t>{8}));
}

TEST(CheckMesh, SliverTriangle) {
  // An open pair of triangles (the border problems are expected); face 0 has two 0.46° angles.
  const MeshReport r = check_text(
      "v 0 0 0\nv 1 0 0\nv 0.5 0.004 0\nv 0.5 -1 0\nvt 0 0\nvt 1 0\nvt 0.5 0.1\nvt 0.5 0.9\n"
      "f 1/1 2/2 3/3\nf 2/2 1/1 4/4\n");
  ASSERT_EQ(faces_with(r, rule::sliver), (std::vector<std::int64_t>{0}));
  const auto it = std::find_if(r.problems.begin(), r.problems.end(), [](const auto& p) { return p.rule == rule::sliver; });
  EXPECT_NEAR(it->value, std::atan(0.008) * 180 / M_PI, 1e-6);  // the angles at both ends of the base
}

// The surface alone: the same surface problems as the whole check, nothing of the UVs (a UV outside
// the unit square and a non-manifold edge planted together).
TEST(CheckMesh, SurfaceCheckLeavesTheUvsOut) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write(
      "m.obj", octahedron_vertices + "v 1 1 1\n" + octahedron_uvs + "vt 0.5 1.25\n" +
                   replace_line(octahedron_faces, "f 1/1 2/2 5/5", "f 1/1 2/10 5/5") + "f 1/1 2/2 7/10\n"));
  const MeshReport whole = check_mesh(mesh, CheckOptions{});
  const MeshReport surface = check_mesh_surface(mesh, CheckOptions{});
  ASSERT_FALSE(faces_with(whole, rule::uv_outside).empty());
  std::vector<MeshProblem> whole_surface_problems;
  for (const MeshProblem& p : whole.problems)
    if (!is_uv_rule(p.rule)) whole_surface_problems.push_back(p);
  ASSERT_EQ(surface.problems.size(), whole_surface_problems.size());
  for (std::size_t i = 0; i < surface.problems.size(); ++i) {
    EXPECT_EQ(surface.problems[i].face, whole_surface_problems[i].face);
    EXPECT_EQ(surface.problems[i].rule, whole_surface_problems[i].rule);
  }
  EXPECT_FALSE(faces_with(surface, rule::non_manifold_edge).empty());
  EXPECT_FALSE(surface.has_uvs);
  EXPECT_EQ(surface.closed, whole.closed);
  EXPECT_EQ(surface.manifold, whole.manifold);
  EXPECT_DOUBLE_EQ(surface.area, whole.area);
  // Without UVs: no no_uvs problem either.
  const MeshReport bare = check_mesh_surface(
      read_proxy_mesh(dir.write("bare.obj", octahedron_vertices + "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 2 1 6\nf 3 2 6\nf 4 3 6\nf 1 4 6\n")),
      CheckOptions{});
  EXPECT_TRUE(bare.problems.empty()) << report_to_text(bare, "bare");
  EXPECT_TRUE(bare.closed && bare.manifold && bare.oriented && bare.outward);
}

TEST(CheckMesh, OpenBorder) {
  // Drop the last face (1, 4, 6): its three edges become border edges of faces 3, 6 and 4.
  const MeshReport r = check_text(octahedron_vertices + octahedron_uvs +
                                  replace_line(octahedron_faces, "f 1/1 4/4 6/9\n", ""));
  EXPECT_EQ(faces_with(r, rule::border_edge), (std::vector<std::int64_t>{3, 4, 6}));
  EXPECT_FALSE(r.closed);
  EXPECT_FALSE(r.volume);
  EXPECT_TRUE(r.manifold && r.oriented);
  // One hole, named once for the whole mesh with its loop count.
  EXPECT_EQ(r.holes, 1u);
  EXPECT_EQ(faces_with(r, rule::holes), (std::vector<std::int64_t>{-1}));
}

// Two faces that share no vertex removed: two boundary loops.
TEST(CheckMesh, HolesAreCountedByBoundaryLoops) {
  const std::string two_holes =
      replace_line(replace_line(octahedron_faces, "f 1/1 4/4 6/9\n", ""), "f 2/2 3/3 5/5\n", "");
  const MeshReport r = check_text(octahedron_vertices + octahedron_uvs + two_holes);
  EXPECT_EQ(r.holes, 2u);
  const auto it = std::find_if(r.problems.begin(), r.problems.end(), [](const auto& p) { return p.rule == rule::holes; });
  ASSERT_NE(it, r.problems.end());
  EXPECT_EQ(it->value, 2.0);
  EXPECT_NE(it->detail.find("6 border edges"), std::string::npos) << it->detail;
  EXPECT_EQ(check_text(testing::octahedron).holes, 0u);
}

TEST(CheckMesh, TooManyTriangles) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write("m.obj", testing::octahedron));
  CheckOptions options;
  options.max_triangles = 7;
  const MeshReport r = check_mesh(mesh, options);
  EXPECT_EQ(faces_with(r, rule::too_many_triangles), (std::vector<std::int64_t>{-1}));
  options.max_triangles = 8;
  EXPECT_TRUE(check_mesh(mesh, options).usable());
}

TEST(CheckMesh, InconsistentAndInwardOrientation) {
  const MeshReport one = check_text(octahedron_vertices + octahedron_uvs +
                                    replace_line(octahedron_faces, "f 1/1 2/2 5/5", "f 2/2 1/1 5/5"));
  EXPECT_FALSE(one.oriented);
  // Face 0 disagrees with its three neighbours 1, 3 and 4; each pair is reported on the later face.
  EXPECT_EQ(faces_with(one, rule::inconsistent_orientation), (std::vector<std::int64_t>{1, 3, 4}));

  std::string reversed = octahedron_vertices + octahedron_uvs;
  for (const char* f : {"f 5/5 2/2 1/1\n", "f 5/5 3/3 2/2\n", "f 5/5 4/4 3/3\n", "f 5/5 1/1 4/4\n",
                        "f 6/6 1/1 2/2\n", "f 6/7 2/2 3/3\n", "f 6/8 3/3 4/4\n", "f 6/9 4/4 1/1\n"})
    reversed += f;
  const MeshReport all = check_text(reversed);
  EXPECT_TRUE(all.closed && all.oriented);
  EXPECT_FALSE(all.outward);
  EXPECT_EQ(faces_with(all, rule::inward_orientation), (std::vector<std::int64_t>{-1}));
  EXPECT_NEAR(*all.volume, -4.0 / 3.0, 1e-6);
}

TEST(CheckMesh, SelfIntersection) {
  // Two closed octahedra, the second shifted by 0.5 along x: they pierce each other.
  std::string text = octahedron_vertices + "v 1.5 0 0\nv 0.5 1 0\nv -0.5 0 0\nv 0.5 -1 0\nv 0.5 0 1\nv 0.5 0 -1\n" +
                     octahedron_uvs + octahedron_faces +
                     "f 7/1 8/2 11/5\nf 8/2 9/3 11/5\nf 9/3 10/4 11/5\nf 10/4 7/1 11/5\n"
                     "f 8/2 7/1 12/6\nf 9/3 8/2 12/7\nf 10/4 9/3 12/8\nf 7/1 10/4 12/9\n";
  const MeshReport r = check_text(text);
  EXPECT_FALSE(faces_with(r, rule::self_intersection).empty());
}

TEST(CheckMesh, JsonHasTheDocumentedKeys) {
  const nlohmann::json j = report_to_json(check_text(testing::octahedron));
  for (const char* key : {"usable", "triangles", "vertices", "closed", "manifold", "oriented", "problems", "seams",
                          "distortion", "uv_scale_k", "replication_area", "area", "volume"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["usable"], true);
  EXPECT_EQ(j["seams"]["edges"], 4);
  EXPECT_EQ(j["replication_area"], nlohmann::json::array({11, 11}));
  EXPECT_TRUE(j["distortion"]["worst"].is_array());
}

TEST(CheckMesh, TextReportNamesFileFaceAndRule) {
  const MeshReport r = check_text(octahedron_vertices + octahedron_uvs + "vt 0.75 0.75\n" +
                                  replace_line(octahedron_faces, "f 1/1 2/2 5/5", "f 1/1 2/2 5/10"));
  const std::string text = report_to_text(r, "cell.obj");
  EXPECT_NE(text.find("cell.obj:face 0: zero-area UV triangle"), std::string::npos) << text;
  EXPECT_NE(text.find("NOT usable"), std::string::npos);
}

TEST(MeshEdges, OctahedronEdgesChartsAndSeams) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write("m.obj", testing::octahedron));
  const auto edges = collect_edges(mesh);
  ASSERT_EQ(edges.size(), 12u);
  int seams = 0;
  for (const MeshEdge& e : edges) {
    EXPECT_EQ(e.uses.size(), 2u);
    EXPECT_NE(e.uses[0].forward, e.uses[1].forward);
    seams += is_seam(mesh, e);
  }
  EXPECT_EQ(seams, 4);
  const auto charts = uv_charts(mesh, edges);
  EXPECT_TRUE(std::all_of(charts.begin(), charts.end(), [](auto c) { return c == 0; }));
  EXPECT_TRUE(non_manifold_vertices(mesh, edges).empty());
}

TEST(ExactPredicates, CollinearAndOrientation) {
  EXPECT_TRUE(exactly_collinear({0, 0, 0}, {1, 1, 1}, {3, 3, 3}));
  // Off the line by one unit in the last place: any tolerance-based test would call it collinear.
  EXPECT_FALSE(exactly_collinear({0, 0, 0}, {1, 1, 0}, {2, 2 + std::ldexp(1.0, -51), 0}));
  EXPECT_EQ(exact_orientation_2d({0, 0}, {1, 0}, {0, 1}), 1);
  EXPECT_EQ(exact_orientation_2d({0, 0}, {0, 1}, {1, 0}), -1);
  EXPECT_EQ(exact_orientation_2d({0, 0}, {0.5, 0.5}, {1, 1}), 0);
}

TEST(AnalyseSolid, OctahedronVolumeAreaAndOutward) {
  TempDir dir;
  const SolidProperties s = analyse_solid(read_proxy_mesh(dir.write("m.obj", testing::octahedron)), true);
  EXPECT_TRUE(s.polygon_mesh && s.closed && s.outward);
  EXPECT_NEAR(*s.volume, 4.0 / 3.0, 1e-12);
  EXPECT_NEAR(s.area, 4 * std::sqrt(3.0), 1e-12);
  EXPECT_TRUE(s.self_intersections.empty());
}

}  // namespace
}  // namespace nano::mesh
