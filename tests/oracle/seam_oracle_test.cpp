// The oracle's seam rule against the baker's enumerator: a hand-built package whose square membrane
// is cut along its diagonal by a UV seam (the two triangles read the tiling at UVs shifted by
// (0.25, 0.125)). The baker's MembraneMapping decides the seam bits and the dropped molecules; the
// package stores those bits and the oracle must place exactly the copies the enumerator keeps, at the
// same positions. The drops themselves are checked against plane geometry in double: a copy of the
// yielding triangle is dropped iff its centre is closer than r + r_max to the diagonal or to one of
// the diagonal's end points.
#include <bit>
#include <cmath>
#include <map>
#include <tuple>

#include <gtest/gtest.h>

#include "bake/shell/membrane_mapping.hpp"
#include "runtime/oracle/explicit_scene.hpp"
#include "tests/oracle/hand_scene.hpp"
#include "tests/oracle/test_package.hpp"

namespace nano::explicit_test {
namespace {

using glm::dvec2;
using glm::dvec3;
using glm::vec2;
using glm::vec4;

using Key = std::tuple<std::uint32_t, int, int, std::uint32_t>;  // triangle (local), cell a, b, instance

const dvec2 kShift(0.25, 0.125);  // UV offset of triangle 1's chart: multiples of 2^-24

struct SeamScene {
  SampleScene scene;
  mesh::ProxyMesh mesh;
  tiles::WangSet set;
  tiles::TilingRecipe recipe;
  std::vector<tiles::MoleculeType> types;
  std::unique_ptr<shell::MembraneMapping> mapping;
  std::uint32_t first_triangle = 0;
};

// The hand scene's squares, molecule types and recipe as the baker's inputs, a seamed square mesh
// mapped with them, and that mesh appended to the package as compartment 3 (the only instance).
std::unique_ptr<SeamScene> seam_scene() {
  auto ss = std::make_unique<SeamScene>();
  SampleScene& s = ss->scene;
  s = hand_scene({{3, {0, 0, 1}, 0, {0, 0, 0}}});
  // Bounding radii padded by 10 Å (still covering the atoms), so that the sparse hand tiles put
  // copies within a radius of the seam.
  for (gpu::MoleculeType& m : s.molecules) m.aabb_min.w += 10.f;
  for (const gpu::MoleculeType& m : s.molecules) {
    tiles::MoleculeType t;
    for (std::uint32_t a = m.first_atom; a < m.first_atom + m.atom_count; ++a)
      t.atoms.push_back({glm::vec3(s.atoms[a].centre_radius), s.atoms[a].centre_radius.w});
    t.bounding_radius = m.aabb_min.w;  // what the package stores and the oracle reads
    ss->types.push_back(t);
  }
  ss->set.dims = 2;
  ss->set.edge = float(kS);
  for (std::uint32_t t = 0; t < 2; ++t) {
    tiles::WangTile tile;
    for (std::uint32_t i = s.tiles2d[t].first_instance; i < s.tiles2d[t].first_instance + s.tiles2d[t].instance_count; ++i) {
      const gpu::MoleculeInstance& in = s.instances[i];
      tile.instances.push_back({in.molecule_type, glm::vec3(in.position), glm::quat(in.rotation.w, in.rotation.x, in.rotation.y, in.rotation.z)});
    }
    ss->set.tiles.push_back(tile);
  }
  ss->recipe.dims = 2;
  ss->recipe.size = {2, 2, 1};
  ss->recipe.cells.assign(s.recipe_indices.begin(), s.recipe_indices.begin() + 4);

  // Square [0, L]² in z = 0, triangles (0,0)-(L,0)-(L,L) and (0,0)-(L,L)-(0,L) sharing the diagonal.
  const double L = kL, k = kK;
  mesh::ProxyMesh& m = ss->mesh;
  m.positions = {{0, 0, 0}, {L, 0, 0}, {L, L, 0}, {0, L, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  for (int t = 0; t < 2; ++t)
    for (int c = 0; c < 3; ++c) {
      const dvec3 p = m.positions[m.triangles[t][c]];
      m.uvs.push_back(dvec2(p) / k + (t == 1 ? kShift : dvec2(0.0)));
    }
  m.uv_triangles = {{0, 1, 2}, {3, 4, 5}};
  m.normals = {{0, 0, 1}};
  m.normal_triangles = {{0, 0, 0}, {0, 0, 0}};
  ss->mapping = std::make_unique<shell::MembraneMapping>(m, ss->set, ss->recipe, k, ss->types);
  const shell::MembraneMapping& map = *ss->mapping;

  const std::uint32_t first_vertex = std::uint32_t(s.vertex_positions.size());
  ss->first_triangle = std::uint32_t(s.triangles.size());
  for (int t = 0; t < 2; ++t) {
    for (int c = 0; c < 3; ++c) {
      s.vertex_positions.push_back(vec4(map.triangle(t).position[c], 0));
      s.vertex_normals.push_back(vec4(0, 0, 1, 0));
      s.vertex_uvs.push_back(map.triangle(t).uv[c]);
    }
    s.triangles.push_back({std::uint32_t(3 * t), std::uint32_t(3 * t + 1), std::uint32_t(3 * t + 2)});
    gpu::TriangleShell shell{vec4(map.triangle(t).uv_min, map.triangle(t).uv_max), 8.0f, 8.0f, 1.0f, map.seam_edges(t)};
    s.triangle_shells.push_back(shell);
  }
  const std::uint32_t mesh_index = std::uint32_t(s.meshes.size());
  s.meshes.push_back({vec4(0, 0, 0, 0), vec4(float(L), float(L), 0, 0), first_vertex, 6, ss->first_triangle, 2});
  gpu::Compartment c{};
  c.scales = vec4(float(kK), float(kS), float(kBox), 0.f);
  c.mesh = mesh_index;
  c.membrane_first_tile = 0;
  c.membrane_tile_count = 2;
  c.membrane_recipe = 0;
  c.soluble_recipe = gpu::NANO_NO_INDEX;
  c.replication_width = std::uint32_t(map.replication_area().x);
  c.replication_height = std::uint32_t(map.replication_area().y);
  s.compartments.push_back(c);
  return ss;
}

std::map<Key, dvec3> enumerated(const shell::MembraneMapping& map, shell::SeamRule rule) {
  std::map<Key, dvec3> out;
  for (std::uint32_t t = 0; t < map.triangle_count(); ++t)
    map.for_each_owned_membrane_molecule(t, [&](const shell::OwnedMolecule& m) {
      out[{t, m.cell.x, m.cell.y, m.instance}] = dvec3(m.transform.translation);
    }, rule);
  return out;
}

double point_segment(dvec3 p, dvec3 a, dvec3 b) {
  const dvec3 ab = b - a;
  const double t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
  return glm::length(p - (a + t * ab));
}

TEST(ExplicitSeam, OracleDropsExactlyWhatTheBakersEnumeratorDrops) {
  const auto ss = seam_scene();
  const shell::MembraneMapping& map = *ss->mapping;
  // Both triangles hold the seam (the diagonal); which bit names it depends on the corner order.
  // Both hold the seam edge itself, so neither is a fan triangle of its end points: no corner bits.
  EXPECT_EQ(map.seam_edges(1), 1u);  // edge 0 (corners 0-1)
  EXPECT_EQ(std::popcount(map.seam_edges(0)), 1);

  const TestPackage pkg(ss->scene);
  const oracle::ExplicitScene scene(pkg.package);
  std::map<Key, dvec3> placed;
  scene.for_each_copy(oracle::WorldBox::everything(), [&](const oracle::Copy& c) {
    ASSERT_EQ(c.id.kind, oracle::CopyKind::membrane);
    const Key key{c.id.element - ss->first_triangle, c.id.cell.x, c.id.cell.y, c.id.instance};
    EXPECT_TRUE(placed.emplace(key, c.origin).second);
  });

  const std::map<Key, dvec3> kept = enumerated(map, shell::SeamRule::apply);
  const std::map<Key, dvec3> all = enumerated(map, shell::SeamRule::ignore);
  ASSERT_EQ(placed.size(), kept.size());
  for (const auto& [key, origin] : kept) {
    const auto it = placed.find(key);
    ASSERT_NE(it, placed.end());
    EXPECT_LT(glm::length(it->second - origin), 1e-4);
  }

  // The drops, from plane geometry: on both triangles, those whose surface point (the centre dropped
  // onto z = 0, the square's plane) lies within their own radius of the diagonal.
  const dvec3 a(0, 0, 0), b(kL, kL, 0);
  std::size_t dropped = 0, dropped_by_triangle[2] = {0, 0};
  for (const auto& [key, origin] : all) {
    const auto& [t, ca, cb, instance] = key;
    const std::uint32_t tile = ss->recipe.at(((ca % 2) + 2) % 2, ((cb % 2) + 2) % 2);
    const double r = ss->types[ss->set.tiles[tile].instances[instance].type].bounding_radius;
    const dvec3 surface(origin.x, origin.y, 0.0);
    const double d = point_segment(surface, a, b);
    ASSERT_GT(std::abs(d - r), 1e-3) << "a copy on the margin makes the comparison fragile";
    const bool drop = d < r;
    EXPECT_EQ(kept.count(key) == 0, drop) << "triangle " << t << " cell " << ca << "," << cb << " #" << instance;
    dropped += drop;
    dropped_by_triangle[t] += drop;
  }
  EXPECT_GT(dropped_by_triangle[0], 0u) << "the scene must exercise the rule on both sides";
  EXPECT_GT(dropped_by_triangle[1], 0u) << "the scene must exercise the rule on both sides";
  EXPECT_EQ(all.size() - kept.size(), dropped);
}

// Without its seam bits the same package keeps everything the triangles own: the oracle reads the
// bits from the package, not from the geometry.
TEST(ExplicitSeam, PackageWithoutSeamBitsKeepsEveryOwnedCopy) {
  auto ss = seam_scene();
  for (gpu::TriangleShell& shell : ss->scene.triangle_shells) shell.seam_edges = 0;
  const TestPackage pkg(ss->scene);
  const oracle::ExplicitScene scene(pkg.package);
  std::size_t n = 0;
  scene.for_each_copy(oracle::WorldBox::everything(), [&](const oracle::Copy&) { ++n; });
  EXPECT_EQ(n, enumerated(*ss->mapping, shell::SeamRule::ignore).size());
  EXPECT_GT(n, enumerated(*ss->mapping, shell::SeamRule::apply).size());
}

}  // namespace
}  // namespace nano::explicit_test
