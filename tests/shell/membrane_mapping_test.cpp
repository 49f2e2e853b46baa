// MembraneMapping on hand-built inputs: UV snapping, the replication area of one triangle over known
// tiles, the wrapped recipe lookup, the owned molecules and their transforms (double oracle), and
// input errors.
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "bake/shell/membrane_mapping.hpp"
#include "common/error.hpp"

using nano::shell::MembraneMapping;
using nano::shell::OwnedMolecule;
using glm::dvec2;
using glm::dvec3;

namespace {

constexpr double kStep = 0x1.0p-24;

bool on_grid(float f) {
  const double q = double(f) / kStep;
  return q == std::floor(q);
}

// One right triangle in z = 0 of legs 100 Å with the given UVs; normals +z.
nano::mesh::ProxyMesh one_triangle(dvec2 t0, dvec2 t1, dvec2 t2) {
  nano::mesh::ProxyMesh m;
  m.positions = {{0, 0, 0}, {100, 0, 0}, {0, 100, 0}};
  m.triangles = {{0, 1, 2}};
  m.uvs = {t0, t1, t2};
  m.uv_triangles = {{0, 1, 2}};
  m.normals = {{0, 0, 1}};
  m.normal_triangles = {{0, 0, 0}};
  return m;
}

// Six distinguishable tiles of edge 200 Å, two instances each; a 3×2 recipe naming tile 0..5.
struct HandTiles {
  nano::tiles::WangSet set;
  nano::tiles::TilingRecipe recipe;
  // One atom of radius 2 Å each: at the origin (radius 2) and 3 Å up (radius 5).
  std::vector<nano::tiles::MoleculeType> types = {{"a", {{{0.f, 0.f, 0.f}, 2.f}}, 2.f, {0, 0, 1}},
                                                  {"b", {{{0.f, 0.f, 3.f}, 2.f}}, 5.f, {0, 0, 1}}};
  HandTiles() {
    set.dims = 2;
    set.edge = 200.f;
    set.tiles.resize(6);
    const glm::quat quarter_turn_z(std::cos(M_PI / 4), 0.f, 0.f, float(std::sin(M_PI / 4)));  // (w, x, y, z)
    for (auto& t : set.tiles) {
      t.instances.push_back({0, {100.f, 100.f, 0.f}, quarter_turn_z});
      t.instances.push_back({1, {13.f, 171.f, 5.f}, glm::quat(1.f, 0.f, 0.f, 0.f)});
    }
    recipe.dims = 2;
    recipe.size = {3, 2, 1};
    recipe.cells = {0, 1, 2, 3, 4, 5};
  }
};

}  // namespace

TEST(UvSnap, MultiplesOfTheOwnershipGridWithinHalfAStep) {
  std::mt19937_64 gen(3);
  for (int i = 0; i < 200000; ++i) {
    const double mag = std::ldexp(1.0, int(gen() % 30) - 26);  // 2^-26 .. 2^3
    const double uv = (std::uniform_real_distribution<double>(-1.0, 1.0)(gen)) * mag;
    const float s = nano::shell::snap_uv(uv);
    ASSERT_TRUE(on_grid(s)) << uv;
    // Half a grid step below 1; beyond, the float spacing (a coarser multiple of the grid) rules.
    const double bound = std::abs(uv) < 1.0 ? kStep / 2 : std::ldexp(1.0, std::ilogb(uv) - 24);
    ASSERT_LE(std::abs(double(s) - uv), bound) << uv;
  }
  EXPECT_EQ(nano::shell::snap_uv(3.0 * kStep + 0.4 * kStep), float(3.0 * kStep));
  EXPECT_EQ(nano::shell::snap_uv(-3.0 * kStep - 0.6 * kStep), float(-4.0 * kStep));
  EXPECT_EQ(nano::shell::snap_uv(dvec2(0.1, 2.5)), glm::vec2(nano::shell::snap_uv(0.1), 2.5f));
}

TEST(MembraneMapping, StoresSnappedMeshUvs) {
  HandTiles h;
  const auto mesh = one_triangle({0.1234567891, 0.13}, {0.47, 0.1300000001}, {0.12, 0.39});
  const MembraneMapping map(mesh, h.set, h.recipe, 2000.0, h.types);
  ASSERT_EQ(map.snapped_uvs().size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(on_grid(map.snapped_uvs()[i].x) && on_grid(map.snapped_uvs()[i].y));
    EXPECT_EQ(map.triangle(0).uv[i], nano::shell::snap_uv(mesh.uvs[i]));
  }
}

// UV offsets: positive cells, and negative cells (exercises the non-negative modulo of the recipe).
class ReplicationArea : public ::testing::TestWithParam<dvec2> {};

TEST_P(ReplicationArea, CoversKnownTilesAndYieldsExactlyTheOwnedMolecules) {
  HandTiles h;
  const dvec2 off = GetParam();
  const dvec2 t0 = dvec2(0.12, 0.13) + off, t1 = dvec2(0.47, 0.13) + off, t2 = dvec2(0.12, 0.39) + off;
  // k = 2000 Å/UV → s = 0.1: the UV box [0.12, 0.47] × [0.13, 0.39] touches cells 1..4 × 1..3.
  const MembraneMapping map(one_triangle(t0, t1, t2), h.set, h.recipe, 2000.0, h.types);
  ASSERT_FLOAT_EQ(map.tile_uv_size(), 0.1f);
  const glm::ivec2 shift(int(std::lround(off.x * 10)), int(std::lround(off.y * 10)));
  EXPECT_EQ(map.triangle(0).origin, glm::ivec2(1, 1) + shift);
  EXPECT_EQ(map.triangle(0).extent, glm::ivec2(4, 3));
  // Bound: ceil(0.35/0.1 + slack) + 1 = 5, ceil(0.26/0.1 + slack) + 1 = 4.
  EXPECT_EQ(map.replication_area(), glm::ivec2(5, 4));

  // Oracle: every instance of every cell around, with its UV in double, strictly inside the triangle.
  const double s = 0.1, S = 200.0;
  std::set<std::tuple<int, int, unsigned>> expected;
  for (int b = -8; b <= 8; ++b)
    for (int a = -8; a <= 8; ++a)
      for (unsigned k = 0; k < 2; ++k) {
        const glm::vec3 p = h.set.tiles[0].instances[k].position;
        const dvec2 uv = dvec2(a, b) * s + dvec2(p.x, p.y) * (s / S) - off;  // relative to the unshifted UVs
        const double l1 = (uv.x - 0.12) / 0.35, l2 = (uv.y - 0.13) / 0.26;
        const double margin = std::min({l1, l2, 1.0 - l1 - l2});
        ASSERT_GT(std::abs(margin), 1e-5) << "fixture puts a molecule on an edge";
        if (margin > 0) expected.insert({a, b, k});
      }
  ASSERT_GE(expected.size(), 3u);

  std::set<std::tuple<int, int, unsigned>> got;
  map.for_each_owned_membrane_molecule(0, [&](const OwnedMolecule& m) {
    got.insert({m.cell.x, m.cell.y, m.instance});
    const int wa = ((m.cell.x % 3) + 3) % 3, wb = ((m.cell.y % 2) + 2) % 2;
    EXPECT_EQ(m.tile, unsigned(wb * 3 + wa));  // recipe cells are numbered x fastest
    EXPECT_EQ(m.tile, map.tile_at(m.cell));
    EXPECT_EQ(m.type, m.instance);
    // World position: x = (u − u0)/0.35·100, y = (v − v0)/0.26·100, z = instance depth (normals +z).
    const glm::vec3 p = h.set.tiles[0].instances[m.instance].position;
    const dvec2 uv = dvec2(m.cell) * s + dvec2(p.x, p.y) * (s / S) - off;
    const dvec3 want((uv.x - 0.12) / 0.35 * 100.0, (uv.y - 0.13) / 0.26 * 100.0, p.z);
    EXPECT_NEAR(glm::length(dvec3(m.transform.translation) - want), 0.0, 2e-3);
    // Quaternion order: instance 0 turns a quarter about z, so x ↦ y (the frame is the identity here).
    const dvec3 x_image = dvec3(m.transform.linear[0]);
    EXPECT_NEAR(glm::length(x_image - (m.instance == 0 ? dvec3(0, 1, 0) : dvec3(1, 0, 0))), 0.0, 1e-6);
  });
  EXPECT_EQ(got, expected);
}

INSTANTIATE_TEST_SUITE_P(Offsets, ReplicationArea, ::testing::Values(dvec2(0.0, 0.0), dvec2(-0.7, -0.5)));

TEST(MembraneMapping, TileAtWrapsNegativeCells) {
  HandTiles h;
  const MembraneMapping map(one_triangle({0.1, 0.1}, {0.3, 0.1}, {0.1, 0.3}), h.set, h.recipe, 2000.0, h.types);
  EXPECT_EQ(map.tile_at({0, 0}), 0u);
  EXPECT_EQ(map.tile_at({2, 1}), 5u);
  EXPECT_EQ(map.tile_at({3, 2}), 0u);
  EXPECT_EQ(map.tile_at({-1, 0}), 2u);
  EXPECT_EQ(map.tile_at({-4, -1}), 5u);
  EXPECT_EQ(map.tile_at({-3, -2}), 0u);
}

TEST(MembraneMapping, DegenerateUvTriangleOwnsNothingAndAddsNoArea) {
  HandTiles h;
  auto mesh = one_triangle({0.1, 0.1}, {0.3, 0.1}, {0.5, 0.1});  // collinear UVs
  const MembraneMapping map(mesh, h.set, h.recipe, 2000.0, h.types);
  EXPECT_FALSE(map.triangle(0).valid);
  EXPECT_EQ(map.replication_area(), glm::ivec2(0, 0));
  int n = 0;
  map.for_each_owned_membrane_molecule(0, [&](const OwnedMolecule&) { ++n; });
  EXPECT_EQ(n, 0);
}

TEST(MembraneMapping, RejectsBadInput) {
  HandTiles h;
  const auto good = one_triangle({0.1, 0.1}, {0.3, 0.1}, {0.1, 0.3});
  auto no_uv = good;
  no_uv.uv_triangles.clear();
  EXPECT_THROW(MembraneMapping(no_uv, h.set, h.recipe, 2000.0, h.types), nano::InputError);
  auto no_normals = good;
  no_normals.normal_triangles.clear();
  EXPECT_THROW(MembraneMapping(no_normals, h.set, h.recipe, 2000.0, h.types), nano::InputError);
  auto far = good;
  far.uvs[1] = {16.0, 0.1};
  EXPECT_THROW(MembraneMapping(far, h.set, h.recipe, 2000.0, h.types), nano::InputError);
  auto nan = good;
  nan.uvs[2].y = NAN;
  EXPECT_THROW(MembraneMapping(nan, h.set, h.recipe, 2000.0, h.types), nano::InputError);
  EXPECT_THROW(MembraneMapping(good, h.set, h.recipe, 0.0, h.types), nano::InputError);
  EXPECT_THROW(MembraneMapping(good, h.set, h.recipe, INFINITY, h.types), nano::InputError);
  auto bad_recipe = h.recipe;
  bad_recipe.cells[4] = 6;
  EXPECT_THROW(MembraneMapping(good, h.set, bad_recipe, 2000.0, h.types), nano::InputError);
  auto cubes = h.set;
  cubes.dims = 3;
  EXPECT_THROW(MembraneMapping(good, cubes, h.recipe, 2000.0, h.types), nano::InputError);
  // The seam rule's radii: every type the set uses must be given, with a radius covering its atoms.
  EXPECT_THROW(MembraneMapping(good, h.set, h.recipe, 2000.0, {h.types[0]}), nano::InputError);
  auto small = h.types;
  small[1].bounding_radius = 4.9f;  // the atom at z = 3 with radius 2 reaches 5 Å
  EXPECT_THROW(MembraneMapping(good, h.set, h.recipe, 2000.0, small), nano::InputError);
  auto unused = h.types;
  unused.push_back({"unused", {{{0.f, 0.f, 9.f}, 1.f}}, 0.f, {0, 0, 1}});  // not in the set: not checked
  EXPECT_NO_THROW(MembraneMapping(good, h.set, h.recipe, 2000.0, unused));
  EXPECT_NO_THROW(MembraneMapping(good, h.set, h.recipe, 2000.0, h.types));
  EXPECT_THROW(MembraneMapping(good, h.set, h.recipe, 2000.0, h.types, "test", nano::shell::SeamRule::ignore, 1.5f), nano::InputError);
  EXPECT_THROW(MembraneMapping(good, h.set, h.recipe, 2000.0, h.types, "test", nano::shell::SeamRule::ignore, NAN), nano::InputError);
  EXPECT_EQ(MembraneMapping(good, h.set, h.recipe, 2000.0, unused).type_radius(1), 5.f);
}
