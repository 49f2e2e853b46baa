// Adaptive shell offsets: every atom sphere of every owned molecule lies inside its triangle's
// prism, by an independent double ray oracle (14 directions per atom centre: odd crossing count and
// nearest crossing ≥ radius). Negative control: the no-overlap prisms (side 0) must fail it.
#include <cstdio>
#include <tuple>

#include <gtest/gtest.h>

#include "bake/grid/triangle_distance.hpp"
#include "common/error.hpp"
#include "shell_test_support.hpp"

using namespace shell_test;
using nano::shell::OwnedMolecule;
namespace g = nano::gpu;

namespace {

struct Tally {
  size_t atoms = 0, failures = 0;
};

// Every atom of every owned molecule against its triangle's reach: its distance to the triangle
// (double, by the grid's closest point) plus its radius never exceeds it. Returns the least slack
// left over a triangle's atoms, the most over triangles (how loose the per-copy sphere bound is).
Tally check_reach(const Scene& sc, const std::vector<float>& reach, double& loosest) {
  const auto& map = *sc.mapping;
  Tally tally;
  loosest = 0;
  for (size_t t = 0; t < map.triangle_count(); ++t) {
    const auto& tm = map.triangle(t);
    const dvec3 p0(tm.position[0]), p1(tm.position[1]), p2(tm.position[2]);
    double farthest = 0;
    bool any = false;
    map.for_each_owned_membrane_molecule(t, [&](const OwnedMolecule& m) {
      const glm::dmat3 lin(m.transform.linear);
      const dvec3 tr(m.transform.translation);
      for (const auto& atom : sc.types[m.type].atoms) {
        ++tally.atoms;
        const double d = std::sqrt(nano::grid::squared_distance_to_triangle(lin * dvec3(atom.centre) + tr, p0, p1, p2)) + atom.radius;
        farthest = std::max(farthest, d), any = true;
        if (d > reach[t]) ++tally.failures;
      }
    });
    if (any) loosest = std::max(loosest, reach[t] - farthest);
    else if (reach[t] != 0.f) ++tally.failures;
  }
  return tally;
}

// Every `stride`-th triangle (the variants need not revisit every atom to make their point).
Tally check_atoms(const Scene& sc, const std::vector<g::ShellOffsets>& offsets, size_t stride = 1) {
  const auto& map = *sc.mapping;
  Tally tally;
  for (size_t t = 0; t < map.triangle_count(); t += stride) {
    const g::Prism pr = nano::shell::triangle_prism(map, t, offsets[t]);
    dvec3 v[6];
    for (int i = 0; i < 6; ++i) v[i] = dvec3(pr.v[i]);
    map.for_each_owned_membrane_molecule(t, [&](const OwnedMolecule& m) {
      const glm::dmat3 lin(m.transform.linear);
      const dvec3 tr(m.transform.translation);
      for (const auto& atom : sc.types[m.type].atoms) {
        ++tally.atoms;
        if (!sphere_in_prism_oracle(v, lin * dvec3(atom.centre) + tr, atom.radius)) ++tally.failures;
      }
    });
  }
  return tally;
}

void check_scene(const Scene& sc, const char* name) {
  const auto r = nano::shell::compute_shell_offsets(*sc.mapping, sc.types);
  const auto& st = r.stats;
  float hp[2] = {1e30f, 0}, hm[2] = {1e30f, 0}, sd[2] = {1e30f, 0};
  for (size_t t = 0; t < r.offsets.size(); ++t) {
    const auto& o = r.offsets[t];
    if (o.h_plus == 0 && o.h_minus == 0 && o.side == 0) continue;
    hp[0] = std::min(hp[0], o.h_plus), hp[1] = std::max(hp[1], o.h_plus);
    hm[0] = std::min(hm[0], o.h_minus), hm[1] = std::max(hm[1], o.h_minus);
    sd[0] = std::min(sd[0], o.side), sd[1] = std::max(sd[1], o.side);
  }
  std::printf("%s: %zu molecules in %zu/%zu triangles; h+ %.2f..%.2f, h- %.2f..%.2f, side %.2f..%.2f Å; "
              "grown %zu (max %d iterations), min cos(n_i, N) %.4f\n",
              name, st.owned_molecules, st.triangles_with_molecules, r.offsets.size(), hp[0], hp[1], hm[0], hm[1],
              sd[0], sd[1], st.grown_triangles, st.max_grow_iterations, st.min_vertex_normal_cos);
  EXPECT_EQ(st.uncontained_triangles, 0u);
  EXPECT_EQ(st.inverted_caps, 0u);
  EXPECT_GT(st.owned_molecules, 1000u);

  const Tally adaptive = check_atoms(sc, r.offsets);
  EXPECT_EQ(adaptive.failures, 0u) << "of " << adaptive.atoms << " atoms";
  ASSERT_EQ(r.reach.size(), r.offsets.size());
  double loosest = 0;
  const Tally within = check_reach(sc, r.reach, loosest);
  std::printf("%s: every atom within its triangle's reach (%zu failures); the bound is at most %.1f Å loose\n", name,
              within.failures, loosest);
  EXPECT_EQ(within.failures, 0u) << "of " << within.atoms << " atoms";
  EXPECT_LT(loosest, 10.0);  // a triangle's reach is its farthest atom, give or take a bounding sphere's slack

  // Fixed shells (the maxima) contain at least as much.
  const std::vector<g::ShellOffsets> fixed(r.offsets.size(), r.fixed);
  EXPECT_EQ(check_atoms(sc, fixed, 4).failures, 0u);

  // Without overlap, molecules on edges stick out of their prism: the oracle must see it.
  std::vector<g::ShellOffsets> no_overlap = r.offsets;
  for (auto& o : no_overlap) o.side = 0.f;
  const Tally flat = check_atoms(sc, no_overlap, 4);
  std::printf("%s: %zu atoms contained; without side offset %zu atoms of every 4th triangle stick out\n", name, adaptive.atoms,
              flat.failures);
  EXPECT_GT(flat.failures, 0u);
}

}  // namespace

TEST(ShellContainment, SphereVirion) { check_scene(*sphere_scene(), "sphere r=500 Å"); }

TEST(ShellContainment, RedBloodCell) { check_scene(*rbc_scene(), "RBC R0=2000 Å"); }

TEST(ShellContainment, OracleRejectsASpherePokingThroughAWall) {
  // Face-parallel unit prism over the right triangle of legs 10, height [−1, 2].
  const dvec3 v[6] = {{0, 0, -1}, {10, 0, -1}, {0, 10, -1}, {0, 0, 2}, {10, 0, 2}, {0, 10, 2}};
  EXPECT_TRUE(sphere_in_prism_oracle(v, {2, 2, 0.5}, 1.4));
  EXPECT_FALSE(sphere_in_prism_oracle(v, {2, 2, 0.5}, 1.6));   // reaches the top cap at 2
  EXPECT_FALSE(sphere_in_prism_oracle(v, {0.5, 3, 0.5}, 0.6));  // reaches the wall x = 0
  EXPECT_FALSE(sphere_in_prism_oracle(v, {-1, 3, 0.5}, 0.1));   // outside
}

TEST(ShellOffsets, MoleculeOriginRadius) {
  nano::tiles::MoleculeType m{"m", {{{3.f, 4.f, 0.f}, 1.f}, {{0.f, 0.f, -2.f}, 3.f}}, 0.f, {0, 0, 1}};
  EXPECT_NEAR(nano::shell::molecule_origin_radius(m), 6.0, 1e-6);
  EXPECT_GE(double(nano::shell::molecule_origin_radius(m)), 6.0);
  m.atoms.push_back({{0.f, 0.f, -6.f}, 1.5f});
  EXPECT_NEAR(nano::shell::molecule_origin_radius(m), 7.5, 1e-6);
  EXPECT_EQ(nano::shell::molecule_origin_radius(nano::tiles::MoleculeType{}), 0.f);
}

TEST(ShellOffsets, FixedIsTheMaximum) {
  const std::vector<g::ShellOffsets> v = {{1.f, 4.f, 0.f}, {3.f, 2.f, 1.5f}, {0.f, 0.f, 0.f}};
  const g::ShellOffsets f = nano::shell::fixed_offsets(v);
  EXPECT_EQ(f.h_plus, 3.f);
  EXPECT_EQ(f.h_minus, 4.f);
  EXPECT_EQ(f.side, 1.5f);
  const g::ShellOffsets z = nano::shell::fixed_offsets({});
  EXPECT_EQ(z.h_plus + z.h_minus + z.side, 0.f);
}

TEST(ShellOffsets, UnknownMoleculeTypeIsAnInputError) {
  const auto sc = sphere_scene();
  EXPECT_THROW(nano::shell::compute_shell_offsets(*sc->mapping, {sc->types[0]}), nano::InputError);
  EXPECT_THROW(nano::shell::compute_shell_offsets(*sc->mapping, {sc->types[0]}, 3), nano::InputError);
}

// Three blocks give bit-identical offsets and statistics to one, and the per-type counts are those
// of the enumerator (the membrane bake takes its copy counts from them).
TEST(ShellOffsets, ThreadCountDoesNotChangeTheResult) {
  const auto sc = rbc_scene();
  const auto one = nano::shell::compute_shell_offsets(*sc->mapping, sc->types, 1);
  const auto three = nano::shell::compute_shell_offsets(*sc->mapping, sc->types, 3);
  ASSERT_EQ(one.offsets.size(), three.offsets.size());
  for (size_t t = 0; t < one.offsets.size(); ++t) {
    EXPECT_EQ(one.offsets[t].h_plus, three.offsets[t].h_plus) << "triangle " << t;
    EXPECT_EQ(one.offsets[t].h_minus, three.offsets[t].h_minus) << "triangle " << t;
    EXPECT_EQ(one.offsets[t].side, three.offsets[t].side) << "triangle " << t;
  }
  EXPECT_EQ(one.reach, three.reach);
  EXPECT_EQ(one.fixed.h_plus, three.fixed.h_plus);
  EXPECT_EQ(one.fixed.side, three.fixed.side);
  EXPECT_EQ(one.stats.owned_molecules, three.stats.owned_molecules);
  EXPECT_EQ(one.stats.triangles_with_molecules, three.stats.triangles_with_molecules);
  EXPECT_EQ(one.stats.grown_triangles, three.stats.grown_triangles);
  EXPECT_EQ(one.stats.max_grow_iterations, three.stats.max_grow_iterations);
  EXPECT_EQ(one.stats.min_vertex_normal_cos, three.stats.min_vertex_normal_cos);

  std::vector<size_t> enumerated(sc->types.size(), 0);
  for (size_t t = 0; t < sc->mapping->triangle_count(); ++t)
    sc->mapping->for_each_owned_membrane_molecule(t, [&](const OwnedMolecule& m) { ++enumerated[m.type]; });
  EXPECT_EQ(one.owned_by_type, enumerated);
  EXPECT_EQ(three.owned_by_type, enumerated);
  EXPECT_GT(one.stats.triangles_with_molecules, 0u);
}

// The shell offsets take their centres from centre_of, which skips the rotation, on the copies of
// for_each_owned_membrane_place: the same copies in the same order as the full enumerator, with
// bit-equal centres, on a smooth surface (both terms of the translation), with and without the seam rule.
TEST(MembraneMapping, CentreEnumerationMatchesTheFullTransformBitForBit) {
  const auto sc = rbc_scene();
  const nano::shell::MembraneMapping smooth(sc->mesh, sc->set, sc->recipe, sc->k, sc->types, "membrane",
                                            nano::shell::SeamRule::apply, 0.5f);
  using Seen = std::tuple<int, int, unsigned, unsigned, float, float, float>;
  for (const auto rule : {nano::shell::SeamRule::apply, nano::shell::SeamRule::ignore}) {
    std::vector<Seen> full, centres;
    for (size_t t = 0; t < smooth.triangle_count(); ++t) {
      smooth.for_each_owned_membrane_molecule(t, [&](const OwnedMolecule& m) {
        const glm::vec3 c = m.transform.translation;
        full.emplace_back(m.cell.x, m.cell.y, m.instance, m.tile, c.x, c.y, c.z);
      }, rule);
      smooth.for_each_owned_membrane_place(t, [&](const nano::shell::OwnedPlace& m) {
        const glm::vec3 c = smooth.centre_of(t, m);
        centres.emplace_back(m.cell.x, m.cell.y, m.instance, m.tile, c.x, c.y, c.z);
      }, rule);
    }
    EXPECT_GT(full.size(), 0u);
    EXPECT_TRUE(full == centres);
  }
}

// The enumerator decides whole tiles at once where it can: it must pick exactly the copies that
// own_triangle_owns picks one by one.
TEST(MembraneMapping, WholeTileDecisionsAgreeWithPerCopyOwnership) {
  const auto sc = rbc_scene();
  const auto& map = *sc->mapping;
  using Copy = std::tuple<int, int, std::uint32_t>;
  for (size_t t = 0; t < map.triangle_count(); ++t) {
    const auto& tm = map.triangle(t);
    std::vector<Copy> per_copy, enumerated;
    for (int j = 0; tm.valid && j < tm.extent.y; ++j)
      for (int i = 0; i < tm.extent.x; ++i) {
        const glm::ivec2 cell = tm.origin + glm::ivec2(i, j);
        const glm::vec2 g = g::replication_tile_uv(cell, map.tile_uv_size());
        const auto& instances = map.set().tiles[map.tile_at(cell)].instances;
        for (std::uint32_t k = 0; k < instances.size(); ++k)
          if (g::own_triangle_owns(tm.uv[0], tm.uv[1], tm.uv[2],
                                   g::chart_molecule_uv(g, map.s_over_S(), instances[k].position)))
            per_copy.emplace_back(cell.x, cell.y, k);
      }
    map.for_each_owned_membrane_place(t, [&](const nano::shell::OwnedPlace& m) {
      enumerated.emplace_back(m.cell.x, m.cell.y, m.instance);
    }, nano::shell::SeamRule::ignore);
    ASSERT_TRUE(per_copy == enumerated) << "triangle " << t;
  }
}

TEST(ShellOffsets, FaceParallelTriangleGetsTheMoleculeReachAndEmptyTrianglesStayFlat) {
  // Flat triangle, normals = face normal (cos = 1): h+ = max(depth + r), h− = max(r − depth) exactly,
  // up to the containment margin and the growth slack.
  nano::tiles::WangSet set;
  set.dims = 2;
  set.edge = 200.f;
  set.tiles.resize(1);
  set.tiles[0].instances = {{0, {100.f, 100.f, 0.f}, glm::quat(1, 0, 0, 0)}, {1, {50.f, 60.f, 5.f}, glm::quat(1, 0, 0, 0)}};
  nano::tiles::TilingRecipe recipe;
  recipe.dims = 2;
  recipe.size = {1, 1, 1};
  recipe.cells = {0};
  const std::vector<nano::tiles::MoleculeType> types = {
      {"a", {{{0.f, 0.f, 0.f}, 2.f}}, 2.f, {0, 0, 1}}, {"b", {{{0.f, 0.f, 1.f}, 2.f}}, 3.f, {0, 0, 1}}};
  nano::mesh::ProxyMesh m;
  // Triangle 0 (UV 0..0.2 with s = 0.1) owns molecules; triangle 1 lies inside cell (5, 5) between them.
  m.positions = {{0, 0, 0}, {400, 0, 0}, {0, 400, 0}, {1000, 1000, 0}, {1010, 1000, 0}, {1000, 1010, 0}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  m.uvs = {{0, 0}, {0.2, 0}, {0, 0.2}, {0.5001, 0.5001}, {0.5011, 0.5001}, {0.5001, 0.5011}};
  m.uv_triangles = {{0, 1, 2}, {3, 4, 5}};
  m.normals = {{0, 0, 1}};
  m.normal_triangles = {{0, 0, 0}, {0, 0, 0}};
  const nano::shell::MembraneMapping map(m, set, recipe, 2000.0, types);
  const auto r = nano::shell::compute_shell_offsets(map, types);
  EXPECT_EQ(r.stats.triangles_with_molecules, 1u);
  EXPECT_GE(r.offsets[0].h_plus, 5.0 + 3.0);
  EXPECT_LE(r.offsets[0].h_plus, 5.0 + 3.0 + 0.05);
  EXPECT_GE(r.offsets[0].h_minus, 2.0);
  EXPECT_LE(r.offsets[0].h_minus, 2.0 + 0.05);
  EXPECT_EQ(r.offsets[1].h_plus, 0.f);
  EXPECT_EQ(r.offsets[1].h_minus, 0.f);
  EXPECT_EQ(r.offsets[1].side, 0.f);
}

// A sphere of 14 Å under lipid sticks 23 Å long: their inner ends would cross the centre, and no
// prism holds one. Each such triangle leaves out what it must (at worst all its copies: a flat
// prism), says so in lipids_left_out and `dropped`, and every copy it keeps lies in its prism (the
// ray oracle); nothing is left uncounted.
TEST(ShellContainment, TrianglesNoPrismFitsLeaveTheirCopiesOutAndSaySo) {
  const auto sc = make_scene(nano::mesh::make_sphere_mesh(300, 14.0));
  const auto& map = *sc->mapping;
  const auto r = nano::shell::compute_shell_offsets(map, sc->types, 2);
  ASSERT_GT(r.stats.uncontained_triangles, 0u) << "every prism fits: the test proves nothing";
  std::vector<std::uint32_t> uncontained = r.uncontained, left_out = r.lipids_left_out;
  std::sort(uncontained.begin(), uncontained.end());
  std::sort(left_out.begin(), left_out.end());
  EXPECT_EQ(left_out, uncontained);
  std::size_t kept = 0, dropped = 0;
  for (const std::uint32_t t : left_out) {
    const g::Prism pr = nano::shell::triangle_prism(map, t, r.offsets[t]);
    dvec3 v[6];
    for (int i = 0; i < 6; ++i) v[i] = dvec3(pr.v[i]);
    map.for_each_owned_membrane_place(t, [&](const nano::shell::OwnedPlace& place) {
      if (std::binary_search(r.dropped[t].begin(), r.dropped[t].end(), map.copy_key(t, place))) {
        ++dropped;
        return;
      }
      ++kept;
      const nano::gpu::Affine3 transform = map.transform_of(t, place);
      for (const auto& atom : sc->types[place.type].atoms)
        EXPECT_TRUE(sphere_in_prism_oracle(v, glm::dmat3(transform.linear) * dvec3(atom.centre) + dvec3(transform.translation),
                                           atom.radius))
            << "triangle " << t;
    }, nano::shell::SeamRule::apply);
  }
  EXPECT_GT(dropped, 0u);
  std::size_t counted = 0;
  for (const std::size_t n : r.dropped_by_type) counted += n;
  EXPECT_GE(counted, dropped);
  std::printf("%zu triangles left %zu copies out and kept %zu\n", left_out.size(), dropped, kept);
}
