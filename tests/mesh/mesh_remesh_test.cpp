// Remeshing for a membrane (bake/mesh/mesh_remesh.hpp), judged by independent means: the distance
// of the new surface from the input by brute force over the input's triangles (Ericson's closest
// point, bake/grid, not CGAL's AABB tree the remesher uses), creases and soundness by check-mesh.
#include "bake/mesh/mesh_remesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "bake/grid/triangle_distance.hpp"
#include "bake/mesh/mesh_check.hpp"
#include "bake/mesh/sphere_mesh.hpp"

namespace nano::mesh {
namespace {

// An axis-aligned box [0, size]³ as 12 outward triangles: 90° creases everywhere, valence-3 corners.
ProxyMesh box(double size) {
  ProxyMesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back(size * glm::dvec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

double distance_to(const ProxyMesh& surface, const glm::dvec3& p) {
  double best = INFINITY;
  for (std::size_t t = 0; t < surface.triangles.size(); ++t)
    best = std::min(best, grid::squared_distance_to_triangle(p, surface.corner_position(t, 0), surface.corner_position(t, 1),
                                                            surface.corner_position(t, 2)));
  return std::sqrt(best);
}

// Vertices, edge midpoints and centroids of `remeshed`, each against `input` by brute force.
double farthest_from(const ProxyMesh& remeshed, const ProxyMesh& input) {
  double farthest = 0.0;
  for (std::size_t t = 0; t < remeshed.triangles.size(); ++t) {
    const glm::dvec3 a = remeshed.corner_position(t, 0), b = remeshed.corner_position(t, 1), c = remeshed.corner_position(t, 2);
    for (const glm::dvec3& p : {a, (a + b) / 2.0, (a + b + c) / 3.0}) farthest = std::max(farthest, distance_to(input, p));
  }
  return farthest;
}

bool sound(const MeshReport& r) {
  return std::all_of(r.problems.begin(), r.problems.end(), [](const MeshProblem& p) { return is_uv_rule(p.rule); });
}

TEST(MeshRemesh, CreasesOfABoxAndOfAFineSphere) {
  EXPECT_NEAR(largest_crease_degrees(box(100.0)), 90.0, 1e-9);
  const ProxyMesh sphere = make_sphere_mesh(6000, 450.0);
  EXPECT_LT(largest_crease_degrees(sphere), kRemeshCreaseDegrees);
  EXPECT_FALSE(remesh_reason(sphere).has_value());
  const std::optional<std::string> reason = remesh_reason(box(100.0));
  ASSERT_TRUE(reason.has_value());
  EXPECT_NE(reason->find("90.0°"), std::string::npos) << *reason;
}

TEST(MeshRemesh, OptionsFollowTheBilayerAndCapTheTriangleCount) {
  const RemeshOptions small = membrane_remesh_options(box(1000.0), 40.0);
  EXPECT_DOUBLE_EQ(small.edge, 20.0);
  EXPECT_DOUBLE_EQ(small.max_distance, 45.0);  // a thickness and a quarter edge
  EXPECT_DOUBLE_EQ(small.crease_radius, 60.0);
  // A box of 10^6 Å: 6·10^12 Å² in at most kRemeshMaxTriangles equilateral triangles.
  const RemeshOptions large = membrane_remesh_options(box(1e6), 40.0);
  EXPECT_NEAR(large.edge, std::sqrt(6e12 / (std::sqrt(3.0) / 4.0 * double(kRemeshMaxTriangles))), 1e-6 * large.edge);
  // Its creases still get half the bilayer, and the bound and radius follow that edge.
  EXPECT_DOUBLE_EQ(large.crease_edge, 20.0);
  EXPECT_DOUBLE_EQ(large.max_distance, 45.0);
  EXPECT_DOUBLE_EQ(large.crease_radius, 60.0);
  EXPECT_DOUBLE_EQ(large.max_edge, kCoarsestEdgeFactor * large.edge);
  // The scene's own edge is kept everywhere.
  const RemeshOptions scene_edge = membrane_remesh_options(box(1e6), 40.0, 70.0);
  EXPECT_DOUBLE_EQ(scene_edge.edge, 70.0);
  EXPECT_DOUBLE_EQ(scene_edge.crease_edge, 70.0);
  EXPECT_DOUBLE_EQ(scene_edge.max_edge, 70.0);
}

TEST(MeshRemesh, ABoxIsRoundedWithinTheBoundAndStaysSound) {
  const ProxyMesh input = box(600.0);
  ProxyMesh m = input;
  const RemeshOptions options = membrane_remesh_options(input, 40.0);
  const RemeshReport r = remesh_for_membrane(m, options, "test", "m.obj");
  EXPECT_EQ(r.triangles_in, 12u);
  EXPECT_EQ(r.triangles_out, m.triangles.size());
  EXPECT_GT(r.triangles_out, 2000u);
  EXPECT_NEAR(r.largest_crease_in, 90.0, 1e-6);
  EXPECT_LT(r.largest_crease_out, 45.0);
  EXPECT_LT(largest_crease_degrees(m), 45.0);
  const double farthest = farthest_from(m, input);
  EXPECT_LE(farthest, options.max_distance) << "the stated bound";
  EXPECT_NEAR(r.max_distance, farthest, 1e-6 * options.max_distance) << "the report measures what the oracle measures";
  EXPECT_GT(farthest, 0.1 * options.max_distance) << "the corners were rounded";
  EXPECT_NEAR(r.volume_in, 600.0 * 600.0 * 600.0, 1e-3);
  EXPECT_NEAR(r.volume_out / r.volume_in, 1.0, 0.05);
  // A box of side a whose 12 edges are rounded with radius R loses (2 − π/2)·R·a of area per edge.
  const double a = 600.0, R = options.crease_radius;
  EXPECT_NEAR(r.area_out / r.area_in, 1.0 - 12.0 * (2.0 - M_PI / 2.0) * R * a / (6.0 * a * a), 0.03);
  const MeshReport check = check_mesh(m, {});
  EXPECT_TRUE(check.closed);
  EXPECT_TRUE(sound(check));
  EXPECT_FALSE(m.has_uvs());
  EXPECT_TRUE(m.has_normals());
  EXPECT_NE(describe(r).find("12 -> "), std::string::npos) << describe(r);
  EXPECT_EQ(to_json(r)["triangles_out"], r.triangles_out);
}

// The largest ratio between the longest edges of two triangles that share an edge.
double largest_neighbour_size_ratio(const ProxyMesh& m) {
  std::vector<double> longest(m.triangles.size());
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> faces_of_edge;
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
      longest[t] = std::max(longest[t], glm::distance(m.positions[a], m.positions[b]));
      faces_of_edge[{std::min(a, b), std::max(a, b)}].push_back(t);
    }
  double largest = 1.0;
  for (const auto& [edge, faces] : faces_of_edge)
    if (faces.size() == 2)
      largest = std::max(largest, std::max(longest[faces[0]], longest[faces[1]]) / std::min(longest[faces[0]], longest[faces[1]]));
  return largest;
}

// A box's flat faces take coarse triangles, level by level out of the finer ones, so that sizes grade
// from the rounded creases outward: no long triangle fans onto a crease's short edges, whose slivers
// the mending would remesh at one size for both (a 1 µm cube lost its coarse levels that way).
TEST(MeshRemesh, ALargeBoxCoarsensItsFacesInGradedLevels) {
  const ProxyMesh input = box(6000.0);
  ProxyMesh m = input;
  RemeshOptions options;
  options.edge = 60.0;
  options.max_distance = 75.0;
  options.crease_radius = 90.0;
  options.max_edge = 960.0;
  options.crease_edge = 30.0;
  const RemeshReport r = remesh_for_membrane(m, options, "test", "m.obj");
  EXPECT_GE(r.coarsest_edge, 480.0);
  // Finer than the uniform pass only along the creases (half its edge, over about 1.5 crease radii),
  // coarser elsewhere: fewer triangles in all (the fanned levels' mending made 211,144 of 166,824 on a
  // box of 6000 Å).
  EXPECT_LT(r.triangles_out, r.triangles_uniform) << describe(r);
  EXPECT_LE(largest_neighbour_size_ratio(m), 5.0);
  EXPECT_LE(farthest_from(m, input), options.max_distance);
  const MeshReport check = check_mesh(m, {});
  EXPECT_TRUE(check.closed);
  EXPECT_TRUE(sound(check));
}

TEST(MeshRemesh, AFineSphereKeepsItsShape) {
  const ProxyMesh input = make_sphere_mesh(2000, 300.0);
  ProxyMesh m = input;
  RemeshOptions options{15.0, 20.0, 60.0};
  const RemeshReport r = remesh_for_membrane(m, options, "test", "m.obj");
  EXPECT_EQ(r.smoothing_steps, 0) << "no crease to round";
  EXPECT_LE(farthest_from(m, input), 2.0);
  EXPECT_NEAR(r.volume_out / r.volume_in, 1.0, 0.01);
}

// An open mesh is input the caller's source names; non-positive options are the caller's bug.
TEST(MeshRemesh, RefusesAnOpenMeshAndNonPositiveOptions) {
  ProxyMesh open = box(100.0);
  open.triangles.pop_back();
  try {
    remesh_for_membrane(open, {10.0, 10.0, 10.0}, "test", {"open.obj", "compartment 'c'"});
    ADD_FAILURE() << "remeshed an open mesh";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "open.obj:compartment 'c': cannot remesh: the mesh has holes");
  }
  ProxyMesh closed = box(100.0);
  EXPECT_THROW(remesh_for_membrane(closed, {0.0, 10.0, 10.0}, "test", "closed.obj"), std::invalid_argument);
  EXPECT_THROW(remesh_for_membrane(closed, {10.0, -1.0, 10.0}, "test", "closed.obj"), std::invalid_argument);
}

}  // namespace
}  // namespace nano::mesh
