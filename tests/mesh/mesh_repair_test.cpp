// "repair": true (bake/mesh/mesh_repair.hpp): each planted defect is mended and said, and check-mesh,
// the independent judge, then finds the surface sound.
#include "bake/mesh/mesh_repair.hpp"

#include <algorithm>
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

TEST(MeshRepair, ClosesAHole) {
  ProxyMesh m = read(kVertices + "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 2 1 6\nf 3 2 6\nf 4 3 6\n");
  ASSERT_EQ(check_mesh(m, {}).holes, 1u);
  const RepairReport r = repair_mesh(m);
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
  const RepairReport r = repair_mesh(m);
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
  const RepairReport r = repair_mesh(m);
  EXPECT_TRUE(r.reoriented);
  EXPECT_TRUE(sound(check_mesh(m, {})));
}

TEST(MeshRepair, LeavesLargeHolesAndSaysSo) {
  ProxyMesh m = read(kVertices + "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n");  // the lower half missing: a 4-edge hole
  const RepairReport r = repair_mesh(m, {.max_hole_edges = 3});
  EXPECT_EQ(r.holes_filled, 0u);
  EXPECT_EQ(r.holes_left, 1u);
  EXPECT_EQ(check_mesh(m, {}).holes, 1u);
  EXPECT_NE(describe(r).find("1 holes too large"), std::string::npos);
}

TEST(MeshRepair, RefusesNonManifoldFaces) {
  // A fin: a third face on edge 1-2.
  ProxyMesh m = read(kVertices + "v 2 2 2\n" + kFaces + "f 1 2 7\n");
  EXPECT_THROW(repair_mesh(m), std::invalid_argument);
}

TEST(MeshRepair, ASoundMeshIsLeftAsItIs) {
  ProxyMesh m = read(kVertices + kFaces);
  const RepairReport r = repair_mesh(m);
  EXPECT_FALSE(r.changed());
  EXPECT_EQ(r.faces_after, 8u);
  EXPECT_EQ(describe(r), "repair: nothing to mend");
}

}  // namespace
}  // namespace nano::mesh
