// "repair": true (bake/mesh/mesh_repair.hpp): each planted defect is mended and said, and check-mesh,
// the independent judge, then finds the surface sound.
#include "bake/mesh/mesh_repair.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "bake/mesh/mesh_check.hpp"
#include "bake/mesh/mesh_reader.hpp"
#include "tests/mesh/test_obj.hpp"

namespace nano::mesh {
namespace {

using testing::TempDir;

const std::string kVertices = "v 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n";
const std::string kFaces = "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 2 1 6\nf 3 2 6\nf 4 3 6\nf 1 4 6\n";

ProxyMesh read(const std::string& obj) {
  TempDir dir;
  return read_proxy_mesh(dir.write("m.obj", obj));
}

bool has_rule(const MeshReport& r, const char* rule) {
  return std::any_of(r.problems.begin(), r.problems.end(), [&](const MeshProblem& p) { return p.rule == rule; });
}

// Shape problems only: the repaired mesh has no UVs, which is the charts' business.
bool sound(const MeshReport& r) {
  return std::all_of(r.problems.begin(), r.problems.end(), [](const MeshProblem& p) { return is_uv_rule(p.rule); });
}

// Closed, manifold, consistently oriented, outward and without any other shape problem.
void expect_sound(const ProxyMesh& m) {
  const MeshReport r = check_mesh(m, {});
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.manifold);
  EXPECT_TRUE(r.oriented);
  EXPECT_TRUE(r.outward);
  EXPECT_TRUE(sound(r)) << report_to_text(r, "repaired");
}

bool says(const RepairReport& r, const std::string& part) { return describe(r).find(part) != std::string::npos; }

// An OBJ written from positions and 0-based triangles (the reader welds equal positions).
std::string obj_text(const std::vector<glm::dvec3>& v, const std::vector<std::array<int, 3>>& f) {
  std::ostringstream out;
  out.precision(17);
  for (const glm::dvec3& p : v) out << "v " << p.x << " " << p.y << " " << p.z << "\n";
  for (const auto& t : f) out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  return out.str();
}

// The octahedron of kVertices/kFaces at `centre`, as OBJ lines numbered after `before` vertices.
std::string octahedron_at(const glm::dvec3& centre, int before) {
  std::vector<glm::dvec3> v{{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const int faces[8][3] = {{1, 2, 5}, {2, 3, 5}, {3, 4, 5}, {4, 1, 5}, {2, 1, 6}, {3, 2, 6}, {4, 3, 6}, {1, 4, 6}};
  std::ostringstream out;
  out.precision(17);
  for (const glm::dvec3& p : v) out << "v " << centre.x + p.x << " " << centre.y + p.y << " " << centre.z + p.z << "\n";
  for (const auto& t : faces) out << "f " << t[0] + before << " " << t[1] + before << " " << t[2] + before << "\n";
  return out.str();
}
std::string two_octahedra(const glm::dvec3& second_centre) {
  return octahedron_at({0, 0, 0}, 0) + octahedron_at(second_centre, 6);
}

// A sphere of `segments` longitudes and 12 latitude bands, outward, with its south cap left out:
// a hole of `segments` border edges.
std::string sphere_without_south_cap(int segments) {
  std::vector<glm::dvec3> v{{0, 0, 1}};
  std::vector<std::array<int, 3>> f;
  const int rings = 11;
  const double pi = std::acos(-1.0);
  for (int i = 1; i <= rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double theta = pi * i / 12, phi = 2 * pi * j / segments;
      v.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    }
  const auto at = [&](int ring, int j) { return 1 + (ring - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) f.push_back({0, at(1, j), at(1, j + 1)});
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      f.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      f.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return obj_text(v, f);
}

// A torus (R 3, r 1, 12 sections of 6) whose tube is pinched to a point at section 0: one closed
// surface whose pinch point joins two fans (two cones tip to tip).
std::string pinched_torus() {
  const int sections = 12, around = 6;
  const double pi = std::acos(-1.0);
  std::vector<glm::dvec3> v{{3, 0, 0}};  // the pinch
  for (int s = 1; s < sections; ++s)
    for (int i = 0; i < around; ++i) {
      const double theta = 2 * pi * s / sections, phi = 2 * pi * i / around;
      v.emplace_back((3 + std::cos(phi)) * std::cos(theta), (3 + std::cos(phi)) * std::sin(theta), std::sin(phi));
    }
  const auto at = [&](int s, int i) { return s % sections == 0 ? 0 : 1 + (s - 1) * around + (i % around); };
  std::vector<std::array<int, 3>> f;
  for (int s = 0; s < sections; ++s)
    for (int i = 0; i < around; ++i) {
      const int a = at(s, i), b = at(s + 1, i), c = at(s + 1, i + 1), d = at(s, i + 1);
      if (a != b && b != c && c != a) f.push_back({a, b, c});
      if (a != c && c != d && d != a) f.push_back({a, c, d});
    }
  return obj_text(v, f);
}

// A Möbius band of 10 quads: one-sided, no orientation agrees across every edge.
std::string moebius_band() {
  const int n = 10;
  const double pi = std::acos(-1.0);
  std::vector<glm::dvec3> v;
  for (int k = 0; k < n; ++k)
    for (double w : {-0.3, 0.3}) {
      const double t = 2 * pi * k / n;
      v.emplace_back((1 + w * std::cos(t / 2)) * std::cos(t), (1 + w * std::cos(t / 2)) * std::sin(t), w * std::sin(t / 2));
    }
  std::vector<std::array<int, 3>> f;
  for (int k = 0; k < n; ++k) {
    const int a = 2 * k, b = 2 * k + 1;
    const int next_a = k + 1 < n ? 2 * (k + 1) : 1, next_b = k + 1 < n ? 2 * (k + 1) + 1 : 0;  // the half twist
    f.push_back({a, next_a, next_b});
    f.push_back({a, next_b, b});
  }
  return obj_text(v, f);
}

TEST(MeshRepair, ClosesAHole) {
  ProxyMesh m = read(kVertices + "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 2 1 6\nf 3 2 6\nf 4 3 6\n");
  ASSERT_EQ(check_mesh(m, {}).holes, 1u);
  const RepairReport r = repair_mesh(m, "m.obj");
  EXPECT_EQ(r.holes_filled, 1u);
  EXPECT_EQ(r.triangles_added, 1u);
  EXPECT_EQ(r.faces_after, 8u);
  const MeshReport after = check_mesh(m, {});
  EXPECT_TRUE(after.closed);
  EXPECT_EQ(after.holes, 0u);
  EXPECT_TRUE(sound(after));
  EXPECT_NE(describe(r).find("1 holes closed with 1 triangles"), std::string::npos) << describe(r);
}

// A vertex on the midpoint of edge 1-2 and a zero-area face (m, 1, 2) closing the T-junction: the
// mesh is closed and manifold, but one face has no area.
TEST(MeshRepair, CollapsesAZeroAreaFace) {
  ProxyMesh m = read(kVertices + "v 0.5 0.5 0\n" + "f 1 7 5\nf 7 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 2 1 6\nf 3 2 6\nf 4 3 6\nf 1 4 6\nf 7 1 2\n");
  const MeshReport before = check_mesh(m, {});
  ASSERT_TRUE(has_rule(before, rule::zero_area));
  ASSERT_TRUE(before.closed);
  const RepairReport r = repair_mesh(m, "m.obj");
  EXPECT_GE(r.degenerate_faces_removed, 1u);
  const MeshReport after = check_mesh(m, {});
  EXPECT_FALSE(has_rule(after, rule::zero_area));
  EXPECT_TRUE(after.closed);
  EXPECT_TRUE(sound(after));
  ASSERT_TRUE(after.volume.has_value());
  EXPECT_NEAR(*after.volume, 4.0 / 3.0, 1e-12);  // the octahedron's volume: nothing else moved
}

TEST(MeshRepair, TurnsAnInsideOutMeshOutward) {
  std::string reversed;
  for (const char* f : {"f 1 5 2\n", "f 2 5 3\n", "f 3 5 4\n", "f 4 5 1\n", "f 2 6 1\n", "f 3 6 2\n", "f 4 6 3\n", "f 1 6 4\n"})
    reversed += f;
  ProxyMesh m = read(kVertices + reversed);
  ASSERT_TRUE(has_rule(check_mesh(m, {}), rule::inward_orientation));
  const RepairReport r = repair_mesh(m, "m.obj");
  EXPECT_TRUE(r.reoriented);
  EXPECT_TRUE(sound(check_mesh(m, {})));
}

TEST(MeshRepair, LeavesLargeHolesAndSaysSo) {
  ProxyMesh m = read(kVertices + "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n");  // the lower half missing: a 4-edge hole
  const RepairReport r = repair_mesh(m, "m.obj", {.max_hole_edges = 3});
  EXPECT_EQ(r.holes_filled, 0u);
  EXPECT_EQ(r.holes_left, 1u);
  EXPECT_EQ(check_mesh(m, {}).holes, 1u);
  EXPECT_NE(describe(r).find("1 holes too large"), std::string::npos);
  EXPECT_EQ(r.largest_hole_left, 4u);
}

// A fin: a third face on edge 1-2 (vertices 0 and 1). Refused, naming the edge and its three faces.
TEST(MeshRepair, RefusesNonManifoldEdgesByName) {
  ProxyMesh m = read(kVertices + "v 2 2 2\n" + kFaces + "f 1 2 7\n");
  ASSERT_TRUE(has_rule(check_mesh(m, {}), rule::non_manifold_edge));
  try {
    repair_mesh(m, {"fin.obj", "compartment 'c'"});
    ADD_FAILURE() << "repaired a non-manifold edge";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "fin.obj");
    EXPECT_EQ(e.where(), "compartment 'c'");
    const std::string what = e.what();
    EXPECT_NE(what.find("3 faces (triangles 0, 4, 8) share the edge between vertex 0 (1, 0, 0) and vertex 1 (0, 1, 0)"),
              std::string::npos) << what;
    EXPECT_NE(what.find("the user's call"), std::string::npos) << what;
  }
  // Two closed octahedra sharing the edge from (1, 0, 0) to (0, 1, 0): four faces on it; which two
  // belong together is a guess.
  ProxyMesh pair = read(two_octahedra({1, 1, 0}));
  ASSERT_TRUE(has_rule(check_mesh(pair, {}), rule::non_manifold_edge));
  try {
    repair_mesh(pair, "m.obj");
    ADD_FAILURE() << "repaired two octahedra sharing an edge";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("4 faces (triangles 0, 4, 10, 14) share the edge between vertex 0 (1, 0, 0) and vertex 1 (0, 1, 0)"),
              std::string::npos) << e.what();
  }
}

TEST(MeshRepair, ASoundMeshIsLeftAsItIs) {
  ProxyMesh m = read(kVertices + kFaces);
  const RepairReport r = repair_mesh(m, "m.obj");
  EXPECT_FALSE(r.changed());
  EXPECT_EQ(r.faces_after, 8u);
  EXPECT_EQ(describe(r), "repair: nothing to mend");
  EXPECT_EQ(r.pieces, 1u);
  EXPECT_EQ(to_json(r)["changed"], false);
}

// Two closed octahedra touching at one vertex: the vertex is split, one copy per octahedron, the
// copies pulled into their own octahedra, and the result is two closed pieces, which is said.
TEST(MeshRepair, SplitsAVertexWhereTwoClosedPiecesTouch) {
  ProxyMesh m = read(two_octahedra({2, 0, 0}));
  ASSERT_EQ(m.positions.size(), 11u);  // (1, 0, 0) welded
  const MeshReport before = check_mesh(m, {});
  ASSERT_TRUE(has_rule(before, rule::non_manifold_vertex));
  ASSERT_TRUE(before.closed);
  const RepairReport r = repair_mesh(m, "m.obj");
  EXPECT_EQ(r.non_manifold_vertices_split, 1u);
  EXPECT_EQ(r.vertex_copies_added, 1u);
  EXPECT_GT(r.split_separation, 0.0);
  EXPECT_LE(r.split_separation, 0.01 * std::sqrt(2.0) + 1e-15);  // 1 % of the shortest edge, √2
  EXPECT_EQ(r.pieces, 2u);
  EXPECT_EQ(r.faces_after, 16u);
  EXPECT_FALSE(r.reoriented);
  EXPECT_TRUE(r.changed());
  EXPECT_TRUE(says(r, "1 non-manifold vertices split (1 copies added")) << describe(r);
  EXPECT_TRUE(says(r, "the result is 2 separate pieces")) << describe(r);
  EXPECT_EQ(to_json(r)["non_manifold_vertices_split"], 1);
  EXPECT_EQ(to_json(r)["pieces"], 2);
  ASSERT_EQ(m.positions.size(), 12u);
  EXPECT_LT(m.positions[0].x, 1.0);   // the first octahedron's copy moved into it,
  EXPECT_GT(m.positions[11].x, 1.0);  // the second's into the second
  expect_sound(m);
  ASSERT_TRUE(check_mesh(m, {}).volume.has_value());
  EXPECT_NEAR(*check_mesh(m, {}).volume, 8.0 / 3.0, 0.02);
}

// One surface pinched to a point (a torus whose tube shrinks to nothing at one place): split, it
// is one closed piece, a sphere bent round until its ends nearly touch.
TEST(MeshRepair, SplitsAPinchedVertexOfOneSurface) {
  ProxyMesh m = read(pinched_torus());
  const MeshReport before = check_mesh(m, {});
  ASSERT_TRUE(has_rule(before, rule::non_manifold_vertex));
  ASSERT_TRUE(before.closed);
  ASSERT_TRUE(before.oriented);
  const RepairReport r = repair_mesh(m, "m.obj");
  EXPECT_EQ(r.non_manifold_vertices_split, 1u);
  EXPECT_EQ(r.pieces, 1u);
  EXPECT_EQ(r.faces_reoriented, 0u);
  EXPECT_FALSE(r.reoriented);
  EXPECT_FALSE(says(r, "pieces")) << describe(r);
  expect_sound(m);
}

// One face of eight wound against its neighbours, the first or a later one: turned to agree (CGAL
// walks from the first face, so for the first it turns the other seven; the repair keeps the
// majority's way and says one face was turned).
TEST(MeshRepair, TurnsAFaceOrientedAgainstItsNeighbours) {
  for (int flipped : {0, 5}) {
    std::vector<std::string> faces{"f 1 2 5\n", "f 2 3 5\n", "f 3 4 5\n", "f 4 1 5\n",
                                   "f 2 1 6\n", "f 3 2 6\n", "f 4 3 6\n", "f 1 4 6\n"};
    faces[flipped] = flipped == 0 ? "f 1 5 2\n" : "f 3 6 2\n";
    std::string text = kVertices;
    for (const std::string& f : faces) text += f;
    ProxyMesh m = read(text);
    ASSERT_TRUE(has_rule(check_mesh(m, {}), rule::inconsistent_orientation));
    const RepairReport r = repair_mesh(m, "m.obj");
    EXPECT_EQ(r.faces_reoriented, 1u) << flipped;
    EXPECT_FALSE(r.reoriented) << flipped;
    EXPECT_TRUE(says(r, "1 faces turned to agree with their neighbours")) << describe(r);
    expect_sound(m);
  }
}

// Inside out but for one face: that face is turned to agree, then the whole turned outward.
TEST(MeshRepair, TurnsOneFaceThenTheWholeMesh) {
  ProxyMesh m = read(kVertices + "f 1 2 5\nf 2 5 3\nf 3 5 4\nf 4 5 1\nf 2 6 1\nf 3 6 2\nf 4 6 3\nf 1 6 4\n");
  const RepairReport r = repair_mesh(m, "m.obj");
  EXPECT_EQ(r.faces_reoriented, 1u);
  EXPECT_TRUE(r.reoriented);
  EXPECT_EQ(r.pieces_turned_over, 1u);
  EXPECT_TRUE(says(r, "turned outward")) << describe(r);
  expect_sound(m);
}

// A hole of exactly max_hole_edges (64) border edges is closed; one of 65 is left and said.
TEST(MeshRepair, ClosesA64EdgeHoleAndLeavesA65EdgeOne) {
  ProxyMesh m = read(sphere_without_south_cap(64));
  const MeshReport before = check_mesh(m, {});
  ASSERT_EQ(before.holes, 1u);
  ASSERT_FALSE(before.closed);
  const RepairReport r = repair_mesh(m, "m.obj");
  EXPECT_EQ(r.holes_filled, 1u);
  EXPECT_EQ(r.triangles_added, 62u);
  EXPECT_EQ(r.holes_left, 0u);
  EXPECT_TRUE(says(r, "1 holes closed with 62 triangles")) << describe(r);
  expect_sound(m);

  ProxyMesh wider = read(sphere_without_south_cap(65));
  const RepairReport left = repair_mesh(wider, "m.obj");
  EXPECT_EQ(left.holes_filled, 0u);
  EXPECT_EQ(left.holes_left, 1u);
  EXPECT_EQ(left.largest_hole_left, 65u);
  EXPECT_FALSE(left.changed());
  EXPECT_TRUE(says(left, "nothing mended; 1 holes too large to close (the largest has 65 border edges)")) << describe(left);
  EXPECT_EQ(check_mesh(wider, {}).holes, 1u);
}

// A face listed twice (the second time wound the other way) is kept once.
TEST(MeshRepair, DropsADuplicateFace) {
  ProxyMesh m = read(kVertices + kFaces + "f 5 2 1\n");
  ASSERT_TRUE(has_rule(check_mesh(m, {}), rule::non_manifold_edge));
  const RepairReport r = repair_mesh(m, "m.obj");
  EXPECT_EQ(r.duplicate_faces_removed, 1u);
  EXPECT_EQ(r.faces_after, 8u);
  EXPECT_TRUE(says(r, "1 duplicate faces dropped")) << describe(r);
  expect_sound(m);
}

// A Möbius band cannot be oriented: refused as one-sided, naming two faces and their edge.
TEST(MeshRepair, RefusesAOneSidedSurface) {
  ProxyMesh m = read(moebius_band());
  try {
    repair_mesh(m, "moebius.obj");
    ADD_FAILURE() << "repaired a Möbius band";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "moebius.obj");
    EXPECT_NE(std::string(e.what()).find("one-sided"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("triangles "), std::string::npos) << e.what();
  }
}

// Faces that all repeat a corner leave nothing to mend: refused from the source the caller names.
TEST(MeshRepair, RefusesAMeshWithNoFaceLeftNamingTheSource) {
  ProxyMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles = {{0, 0, 1}, {1, 2, 2}};
  try {
    repair_mesh(m, {"slivers.obj", "compartment 'cell'"});
    ADD_FAILURE() << "repaired a mesh of repeated corners";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "slivers.obj:compartment 'cell': cannot repair: no face is left");
  }
}

// Two separate closed octahedra need nothing; the report still says there are two pieces.
TEST(MeshRepair, SaysWhenASoundMeshIsSeveralPieces) {
  ProxyMesh m = read(two_octahedra({5, 0, 0}));
  const RepairReport r = repair_mesh(m, "m.obj");
  EXPECT_FALSE(r.changed());
  EXPECT_EQ(r.pieces, 2u);
  EXPECT_EQ(describe(r), "repair: nothing to mend (the mesh is 2 separate pieces)");
  expect_sound(m);
}

}  // namespace
}  // namespace nano::mesh
