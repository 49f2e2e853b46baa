// Clash pruning on the real surface (bake/shell/membrane_pruning.hpp), against a brute-force double
// check of every pair of kept copies that shares no code with the pruner (its own spatial hash, its
// own atom distances from the placed transforms):
//  * without pruning, charts meeting at UV seams overlap; after it no two kept copies clash, on the
//    sphere (pruned everywhere) and on the red blood cell (pruned along its seam only);
//  * it drops few copies: each dropped copy clashed with a kept one, and far fewer go than the
//    seam rule's empty bands cost;
//  * the keys name exactly the dropped (slot, instance) of each triangle, ascending;
//  * the result does not depend on the number of threads.
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>

#include <gtest/gtest.h>

#include "bake/shell/membrane_pruning.hpp"
#include "shell_test_support.hpp"
#include "shared/render_membrane_filter.h"

using namespace shell_test;
using nano::shell::MembraneMapping;
using nano::shell::OwnedMolecule;
using nano::shell::PrunedMembrane;
using nano::shell::PruningSettings;
using nano::shell::SeamRule;

namespace {

struct Copy {
  std::uint32_t triangle, key, type;
  dvec3 centre;
  glm::dmat3 rotation;
  bool alternate = false;  // tiles::Instance::alternate
};

// Every owned copy with its key (slot relative to the triangle's replication origin, W of the mapping).
std::vector<Copy> owned_copies(const MembraneMapping& map) {
  std::vector<Copy> out;
  const std::uint32_t W = std::uint32_t(map.replication_area().x);
  for (std::size_t t = 0; t < map.triangle_count(); ++t) {
    const glm::ivec2 origin = map.triangle(t).origin;
    map.for_each_owned_membrane_molecule(
        t,
        [&](const OwnedMolecule& m) {
          const glm::ivec2 slot = m.cell - origin;
          out.push_back({std::uint32_t(t), (std::uint32_t(slot.x + int(W) * slot.y) << 16) | m.instance, m.type,
                         dvec3(m.transform.translation), glm::dmat3(m.transform.linear),
                         map.set().tiles[m.tile].instances[m.instance].alternate});
        },
        SeamRule::ignore);
  }
  return out;
}

bool dropped(const PrunedMembrane& p, const Copy& c) {
  const auto& keys = p.dropped[c.triangle];
  return std::binary_search(keys.begin(), keys.end(), c.key);
}

// Pairs of copies (index pairs) with atoms closer than clearance · (r1 + r2), in double.
std::vector<std::pair<std::size_t, std::size_t>> clashes(const std::vector<Copy>& copies,
                                                         const std::vector<nano::tiles::MoleculeType>& types,
                                                         double clearance) {
  double reach = 0.0;
  std::vector<double> radius;
  for (const auto& t : types) {
    double r = 0.0;
    for (const auto& a : t.atoms) r = std::max(r, glm::length(dvec3(a.centre)) + a.radius);
    radius.push_back(r);
    reach = std::max(reach, r);
  }
  const double cell = 2.0 * reach;
  std::unordered_map<long long, std::vector<std::size_t>> grid;
  auto key = [&](glm::ivec3 c) { return (long long)(c.x + 4096) * 8192 * 8192 + (long long)(c.y + 4096) * 8192 + (c.z + 4096); };
  for (std::size_t i = 0; i < copies.size(); ++i) grid[key(glm::ivec3(glm::floor(copies[i].centre / cell)))].push_back(i);
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t i = 0; i < copies.size(); ++i) {
    const glm::ivec3 c(glm::floor(copies[i].centre / cell));
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          auto it = grid.find(key(c + glm::ivec3(dx, dy, dz)));
          if (it == grid.end()) continue;
          for (std::size_t j : it->second) {
            if (j <= i) continue;
            const Copy& a = copies[i];
            const Copy& b = copies[j];
            if (glm::length(a.centre - b.centre) >= radius[a.type] + radius[b.type]) continue;
            bool hit = false;
            for (const auto& x : types[a.type].atoms)
              for (const auto& y : types[b.type].atoms) {
                const dvec3 pa = a.centre + a.rotation * dvec3(x.centre), pb = b.centre + b.rotation * dvec3(y.centre);
                hit = hit || glm::length(pa - pb) < clearance * (x.radius + y.radius);
              }
            if (hit) out.emplace_back(i, j);
          }
        }
  }
  return out;
}

void expect_clash_free_after_pruning(Scene& sc, const PruningSettings& settings, bool expect_whole) {
  const MembraneMapping map(sc.mesh, sc.set, sc.recipe, sc.k, sc.types, "test", SeamRule::ignore);
  const std::vector<Copy> all = owned_copies(map);
  const auto before = clashes(all, sc.types, 0.6);
  ASSERT_GT(before.size(), 0u) << "the charts must overlap at their seams, or the test proves nothing";

  const PrunedMembrane p = nano::shell::prune_membrane(map, sc.mesh, sc.types, settings, 2);
  EXPECT_EQ(p.whole_surface, expect_whole);
  EXPECT_EQ(p.owned_copies, all.size());
  std::vector<Copy> kept;
  std::set<std::size_t> dropped_index;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (dropped(p, all[i])) dropped_index.insert(i);
    else kept.push_back(all[i]);
  }
  EXPECT_EQ(dropped_index.size(), p.dropped_count()) << "every key names an owned copy";
  EXPECT_GT(p.dropped_count(), 0u);
  const auto after = clashes(kept, sc.types, 0.6);
  EXPECT_EQ(after.size(), 0u) << "kept copies still clash";
  // Few drops: each dropped copy clashed with one that was kept.
  std::set<std::size_t> kept_index;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (!dropped_index.count(i)) kept_index.insert(i);
  std::set<std::size_t> justified;
  for (const auto& [i, j] : before) {
    if (dropped_index.count(i) && kept_index.count(j)) justified.insert(i);
    if (dropped_index.count(j) && kept_index.count(i)) justified.insert(j);
  }
  EXPECT_EQ(justified.size(), dropped_index.size()) << "a copy was dropped that clashed with no kept copy";
  for (const auto& keys : p.dropped) EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
  // The seam rule empties a band on both sides of every seam; pruning drops fewer copies.
  const MembraneMapping banded(sc.mesh, sc.set, sc.recipe, sc.k, sc.types, "test", SeamRule::apply);
  EXPECT_LT(p.dropped_count(), banded.seam_dropped_count());
}

// The test scenes' membrane with lipids packed as densely as a real bilayer's (65 Å² per lipid per
// leaflet): the sparse default never meets across a seam of the sphere.
std::unique_ptr<Scene> dense(std::unique_ptr<Scene> sc) {
  nano::tiles::MembraneTileRequest r;
  r.types = sc->types;
  r.edge = 200.f;
  r.colours = 2;
  r.molecules = {{1, 1.0 / (200.0 * 200.0 * 1e-8), 22.f}};
  r.lipids = nano::tiles::LipidFill{0, 65.f, 16.f};
  r.seed = 5;
  sc->set = nano::tiles::make_membrane_tiles(r);
  return sc;
}

TEST(MembranePruning, SphereIsClashFreeEverywhere) {
  auto sc = dense(sphere_scene());
  expect_clash_free_after_pruning(*sc, PruningSettings{}, true);
}

TEST(MembranePruning, RedBloodCellIsClashFreeAlongItsSeam) {
  auto sc = rbc_scene();
  PruningSettings seams_only;
  seams_only.whole_surface_budget = 0;  // as a full-size cell is: only copies within reach of a seam
  expect_clash_free_after_pruning(*sc, seams_only, false);
}

TEST(MembranePruning, SameResultOnOneAndTwoThreads) {
  auto sc = dense(sphere_scene());
  const MembraneMapping map(sc->mesh, sc->set, sc->recipe, sc->k, sc->types, "test", SeamRule::ignore);
  const PrunedMembrane one = nano::shell::prune_membrane(map, sc->mesh, sc->types, {}, 1);
  const PrunedMembrane two = nano::shell::prune_membrane(map, sc->mesh, sc->types, {}, 2);
  EXPECT_EQ(one.dropped, two.dropped);
  EXPECT_EQ(one.dropped_by_type, two.dropped_by_type);
}

// The pruner's clash search (atoms binned by chunk) finds exactly the pairs the brute-force double
// check finds over every owned copy, at the pruner's clearance and at a wider one.
TEST(MembranePruning, ClashingPairsAreExactlyTheBruteForceOnes) {
  auto sc = dense(sphere_scene());
  const MembraneMapping map(sc->mesh, sc->set, sc->recipe, sc->k, sc->types, "test", SeamRule::ignore);
  const std::vector<Copy> all = owned_copies(map);
  for (const float clearance : {0.6012f, 0.9f}) {
    PruningSettings settings;
    settings.clearance = clearance;
    settings.whole_surface = true;
    const PrunedMembrane p = nano::shell::prune_membrane(map, sc->mesh, sc->types, settings, 2);
    const auto expected = clashes(all, sc->types, clearance);
    ASSERT_GT(expected.size(), 0u);
    EXPECT_EQ(p.clashing_pairs, expected.size()) << "clearance " << clearance;
    EXPECT_GT(p.atom_pairs, p.clashing_pairs);
    EXPECT_GT(p.copy_pairs_tested, 0u) << "the proteins' pairs are tested copy against copy";
    EXPECT_EQ(p.checked_copies, all.size());
  }
}

// Triangles checked whole (PruningSettings::checked_triangles) on a membrane otherwise checked along
// its seams only: with every triangle marked, exactly what checking the whole surface drops.
TEST(MembranePruning, AllTrianglesCheckedIsTheWholeSurface) {
  auto sc = dense(sphere_scene());
  const MembraneMapping map(sc->mesh, sc->set, sc->recipe, sc->k, sc->types, "test", SeamRule::ignore);
  const PrunedMembrane whole = nano::shell::prune_membrane(map, sc->mesh, sc->types, {}, 2);
  PruningSettings marked;
  marked.whole_surface_budget = 0;
  marked.checked_triangles.assign(sc->mesh.triangles.size(), 1);
  const PrunedMembrane all = nano::shell::prune_membrane(map, sc->mesh, sc->types, marked, 2);
  ASSERT_TRUE(whole.whole_surface);
  EXPECT_FALSE(all.whole_surface);
  EXPECT_EQ(all.checked_triangles, sc->mesh.triangles.size());
  EXPECT_EQ(all.checked_copies, whole.checked_copies);
  EXPECT_EQ(all.dropped, whole.dropped);
}

// Marked triangles (the northern cap of the sphere), on a chart that squeezes the tiles everywhere:
// no kept copy on them clashes with any kept copy, on them or beside them (brute force); elsewhere,
// away from the seams, clashes are left, so the marking is what made the cap clash-free.
TEST(MembranePruning, CheckedTrianglesAndTheirNeighboursAreClashFree) {
  auto sc = dense(sphere_scene());
  sc->k *= 1.6;  // tiles squeezed to 5/8 of their size on the surface: copies clash everywhere
  const MembraneMapping map(sc->mesh, sc->set, sc->recipe, sc->k, sc->types, "test", SeamRule::ignore);
  PruningSettings settings;
  settings.whole_surface_budget = 0;
  settings.checked_triangles.assign(sc->mesh.triangles.size(), 0);
  std::size_t marked = 0;
  for (std::size_t t = 0; t < sc->mesh.triangles.size(); ++t) {
    const dvec3 c = (sc->mesh.corner_position(t, 0) + sc->mesh.corner_position(t, 1) + sc->mesh.corner_position(t, 2)) / 3.0;
    if (c.z > 0.5 * 500.0) settings.checked_triangles[t] = 1, ++marked;
  }
  ASSERT_GT(marked, 10u);
  const PrunedMembrane p = nano::shell::prune_membrane(map, sc->mesh, sc->types, settings, 2);
  EXPECT_EQ(p.checked_triangles, marked);
  const std::vector<Copy> all = owned_copies(map);
  std::vector<Copy> kept;
  for (const Copy& c : all)
    if (!dropped(p, c)) kept.push_back(c);
  std::size_t on_cap = 0, elsewhere = 0;
  for (const auto& [i, j] : clashes(kept, sc->types, 0.6))
    (settings.checked_triangles[kept[i].triangle] || settings.checked_triangles[kept[j].triangle] ? on_cap : elsewhere)++;
  EXPECT_EQ(on_cap, 0u) << "kept copies clash on or beside the checked triangles";
  EXPECT_GT(elsewhere, 0u) << "the rest of the sphere was not checked, or the test proves nothing";
  // Without the marks, the cap keeps clashing copies too: the marks are what cleared it.
  PruningSettings unmarked = settings;
  unmarked.checked_triangles.clear();
  const PrunedMembrane q = nano::shell::prune_membrane(map, sc->mesh, sc->types, unmarked, 2);
  std::vector<Copy> kept_unmarked;
  for (const Copy& c : all)
    if (!dropped(q, c)) kept_unmarked.push_back(c);
  std::size_t cap_unmarked = 0;
  for (const auto& [i, j] : clashes(kept_unmarked, sc->types, 0.6))
    cap_unmarked += settings.checked_triangles[kept_unmarked[i].triangle] && settings.checked_triangles[kept_unmarked[j].triangle];
  EXPECT_GT(cap_unmarked, 0u);
}

// limit_copies keeps exactly N of a type, a subset of what pruning kept, spread out: farthest-point
// sampling keeps every other copy nearer to a kept one than any two kept copies are to each other.
TEST(MembranePruning, LimitCopiesKeepsASpreadSubset) {
  auto sc = dense(sphere_scene());
  const MembraneMapping map(sc->mesh, sc->set, sc->recipe, sc->k, sc->types, "test", SeamRule::ignore);
  PrunedMembrane p = nano::shell::prune_membrane(map, sc->mesh, sc->types, {}, 2);
  const std::vector<Copy> all = owned_copies(map);
  std::vector<Copy> before;
  for (const Copy& c : all)
    if (c.type == 1 && !dropped(p, c)) before.push_back(c);
  ASSERT_GT(before.size(), 12u);
  const std::uint64_t dropped_before = p.dropped_count();
  std::vector<bool> lipid_dropped_before;
  for (const Copy& c : all)
    if (c.type == 0) lipid_dropped_before.push_back(dropped(p, c));
  EXPECT_EQ(nano::shell::limit_copies(map, p, 1, 12), 12u);
  std::vector<bool> lipid_dropped_after;
  for (const Copy& c : all)
    if (c.type == 0) lipid_dropped_after.push_back(dropped(p, c));
  EXPECT_EQ(lipid_dropped_after, lipid_dropped_before) << "limiting the proteins dropped a lipid";
  std::vector<Copy> kept;
  for (const Copy& c : before)
    if (!dropped(p, c)) kept.push_back(c);
  ASSERT_EQ(kept.size(), 12u);
  EXPECT_EQ(p.dropped_count(), dropped_before + before.size() - 12);
  for (const auto& keys : p.dropped) EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
  double closest_kept = INFINITY, farthest_covered = 0.0;
  for (std::size_t i = 0; i < kept.size(); ++i)
    for (std::size_t j = i + 1; j < kept.size(); ++j) closest_kept = std::min(closest_kept, glm::length(kept[i].centre - kept[j].centre));
  for (const Copy& c : before) {
    double nearest = INFINITY;
    for (const Copy& k : kept) nearest = std::min(nearest, glm::length(c.centre - k.centre));
    farthest_covered = std::max(farthest_covered, nearest);
  }
  EXPECT_LE(farthest_covered, closest_kept + 1e-3);
  EXPECT_EQ(nano::shell::limit_copies(map, p, 1, 100), 12u);  // fewer than asked: all kept
}

// Counts settled before the pruning (limit_copies on an empty result, then dropped_before): the
// copies dropped then are dropped in the result too, are never placed, so no copy is dropped for
// clashing with one of them, and what is kept is clash-free.
TEST(MembranePruning, CopiesDroppedBeforeTakeNothingWithThem) {
  auto sc = dense(sphere_scene());
  const MembraneMapping map(sc->mesh, sc->set, sc->recipe, sc->k, sc->types, "test", SeamRule::ignore);
  PrunedMembrane limited;
  limited.dropped.assign(map.triangle_count(), {});
  limited.dropped_by_type.assign(sc->types.size(), 0);
  ASSERT_EQ(nano::shell::limit_copies(map, limited, 1, 4), 4u);
  PruningSettings settings;
  settings.dropped_before = limited.dropped;
  const PrunedMembrane p = nano::shell::prune_membrane(map, sc->mesh, sc->types, settings, 2);
  const std::vector<Copy> all = owned_copies(map);
  std::vector<Copy> kept;
  std::set<std::size_t> dropped_now, kept_index;
  std::size_t proteins_kept = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const bool before = dropped(limited, all[i]);
    if (before) {
      EXPECT_TRUE(dropped(p, all[i])) << "a copy dropped before came back";
    }
    if (dropped(p, all[i])) {
      if (!before) dropped_now.insert(i);
    } else {
      kept.push_back(all[i]);
      kept_index.insert(i);
      proteins_kept += all[i].type == 1;
    }
  }
  EXPECT_LE(proteins_kept, 4u);
  EXPECT_EQ(p.checked_copies, all.size() - limited.dropped_count());
  EXPECT_EQ(clashes(kept, sc->types, 0.6).size(), 0u);
  std::set<std::size_t> justified;
  for (const auto& [i, j] : clashes(all, sc->types, 0.6)) {
    if (dropped_now.count(i) && kept_index.count(j)) justified.insert(i);
    if (dropped_now.count(j) && kept_index.count(i)) justified.insert(j);
  }
  EXPECT_EQ(justified.size(), dropped_now.size()) << "a copy was dropped for a neighbour that was dropped before";
}

}  // namespace

// Alternates (tiles::Instance::alternate): here a thinner lipid at the place of every lipid. Each is
// listed (shown) only where it fits among everything else shown; its original is dropped there
// first, and no two shown copies clash (the brute-force check).
TEST(MembranePruning, AlternatesShowOnlyWhereTheyFit) {
  auto sc = dense(sphere_scene());
  nano::tiles::MoleculeType thin = sc->types[0];
  thin.name = "thin";
  for (auto& a : thin.atoms) a.radius *= 0.5f;
  sc->types.push_back(thin);
  const std::uint32_t thin_type = std::uint32_t(sc->types.size() - 1);
  for (auto& tile : sc->set.tiles) {
    const std::size_t n = tile.instances.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (tile.instances[i].type != 0) continue;
      tile.instances[i].has_alternate = true;
      nano::tiles::Instance alternate = tile.instances[i];
      alternate.type = thin_type;
      alternate.alternate = true;
      alternate.has_alternate = false;
      tile.instances.push_back(alternate);
    }
  }
  const MembraneMapping map(sc->mesh, sc->set, sc->recipe, sc->k, sc->types, "test", SeamRule::ignore);
  const PrunedMembrane p = nano::shell::prune_membrane(map, sc->mesh, sc->types, PruningSettings{}, 2);
  ASSERT_TRUE(p.whole_surface);
  const std::vector<Copy> all = owned_copies(map);
  std::vector<Copy> shown;
  std::size_t alternates_shown = 0, regular_dropped = 0;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> place;  // (triangle, key) -> index
  for (std::size_t i = 0; i < all.size(); ++i) place[{all[i].triangle, all[i].key}] = i;
  for (const Copy& c : all) {
    const bool alternate = c.type == thin_type;
    const bool listed = dropped(p, c);
    if (nano::gpu::membrane_copy_listed_shows(listed, alternate ? nano::gpu::NANO_INSTANCE_ALTERNATE : 0u)) shown.push_back(c);
    alternates_shown += alternate && listed;
    regular_dropped += !alternate && listed;
  }
  EXPECT_GT(alternates_shown, 0u) << "the thin lipid fits where some lipids clash, or the test proves nothing";
  EXPECT_LT(alternates_shown, regular_dropped + 1) << "an alternate shows only where its lipid was dropped";
  EXPECT_EQ(p.alternates_by_type[thin_type], alternates_shown);
  EXPECT_EQ(p.dropped_by_type[0] + p.dropped_by_type[1], regular_dropped);
  EXPECT_EQ(p.dropped_by_type[thin_type], 0u);
  EXPECT_EQ(clashes(shown, sc->types, 0.6).size(), 0u) << "shown copies clash";
}

// Alternates of a lipid's own type standing 3 Å aside (bake/tiles/wang_sets.cpp puts lipids 1 Å
// aside): two stick lipids 3 Å apart do not clash at 0.6 · (r1 + r2) = 2.04 Å, yet they are one place
// held twice. An alternate is shown only where no copy of its type holds its place, though some are.
TEST(MembranePruning, AnAlternateNeverSharesItsPlaceWithOneOfItsType) {
  auto sc = dense(sphere_scene());
  for (auto& tile : sc->set.tiles) {
    const std::size_t n = tile.instances.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (tile.instances[i].type != 0) continue;
      nano::tiles::Instance aside = tile.instances[i];
      aside.position.x += 3.f;
      aside.alternate = true;
      tile.instances.push_back(aside);
    }
  }
  const MembraneMapping map(sc->mesh, sc->set, sc->recipe, sc->k, sc->types, "test", SeamRule::ignore);
  const PrunedMembrane p = nano::shell::prune_membrane(map, sc->mesh, sc->types, PruningSettings{}, 2);
  ASSERT_TRUE(p.whole_surface);
  std::vector<Copy> shown;
  std::vector<char> shown_alternate;
  for (const Copy& c : owned_copies(map))
    if (nano::gpu::membrane_copy_listed_shows(dropped(p, c), c.alternate ? nano::gpu::NANO_INSTANCE_ALTERNATE : 0u)) {
      shown.push_back(c);
      shown_alternate.push_back(c.alternate);
    }
  std::size_t alternates_shown = 0;
  for (std::size_t i = 0; i < shown.size(); ++i) {
    if (!shown_alternate[i]) continue;
    ++alternates_shown;
    for (std::size_t j = 0; j < shown.size(); ++j) {
      if (j == i || shown[j].type != shown[i].type) continue;
      EXPECT_GE(glm::length(shown[j].centre - shown[i].centre), 3.5) << "an alternate shown where a copy of its type stands";
    }
  }
  EXPECT_GT(alternates_shown, 0u) << "an alternate fits where its lipid was dropped, or the test proves nothing";
  EXPECT_EQ(p.alternates_by_type[0], alternates_shown);
  EXPECT_EQ(clashes(shown, sc->types, 0.6).size(), 0u) << "shown copies clash";
}

// swap_one_for_two on small conflict graphs, against the rule checked by brute force.
namespace {

using Graph = std::vector<std::vector<std::uint32_t>>;

Graph graph(std::size_t n, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges) {
  Graph g(n);
  for (const auto& [a, b] : edges) g[a].push_back(b), g[b].push_back(a);
  for (auto& list : g) std::sort(list.begin(), list.end());
  return g;
}

bool clash_in(const Graph& g, std::uint32_t a, std::uint32_t b) { return std::count(g[a].begin(), g[a].end(), b) > 0; }

// A kept swappable copy holding out two swappable dropped ones that clash with nothing else kept nor
// with each other, and no unswappable one that nothing else holds out.
bool one_for_two_left(const Graph& g, const std::vector<char>& swappable, const std::vector<char>& kept) {
  for (std::uint32_t c = 0; c < g.size(); ++c) {
    if (!kept[c] || !swappable[c]) continue;
    std::vector<std::uint32_t> alone;
    bool needed = false;
    for (const std::uint32_t d : g[c])
      if (!kept[d] && std::count_if(g[d].begin(), g[d].end(), [&](std::uint32_t x) { return kept[x] != 0; }) == 1) {
        if (swappable[d]) alone.push_back(d);
        else needed = true;
      }
    if (needed) continue;
    for (std::size_t i = 0; i < alone.size(); ++i)
      for (std::size_t j = i + 1; j < alone.size(); ++j)
        if (!clash_in(g, alone[i], alone[j])) return true;
  }
  return false;
}

}  // namespace

TEST(SwapOneForTwo, TwoCopiesTakeThePlaceOfTheOneHoldingThemOut) {
  // 0 - 2 - 1: 2 kept holds out 0 and 1.
  const Graph path = graph(3, {{0, 2}, {1, 2}});
  std::vector<char> kept{0, 0, 1};
  nano::shell::swap_one_for_two(path, {1, 1, 1}, kept);
  EXPECT_EQ(kept, (std::vector<char>{1, 1, 0}));
  // The same with 2 a protein: it stays.
  kept = {0, 0, 1};
  nano::shell::swap_one_for_two(path, {1, 1, 0}, kept);
  EXPECT_EQ(kept, (std::vector<char>{0, 0, 1}));
  // 0 and 1 clash with each other too: only one could take 2's place, nothing changes.
  kept = {0, 0, 1};
  nano::shell::swap_one_for_two(graph(3, {{0, 2}, {1, 2}, {0, 1}}), {1, 1, 1}, kept);
  EXPECT_EQ(kept, (std::vector<char>{0, 0, 1}));
  // 1 is also held out by 3, kept: 2 holds out 0 alone, nothing changes.
  kept = {0, 0, 1, 1};
  nano::shell::swap_one_for_two(graph(4, {{0, 2}, {1, 2}, {1, 3}}), {1, 1, 1, 1}, kept);
  EXPECT_EQ(kept, (std::vector<char>{0, 0, 1, 1}));
}

TEST(SwapOneForTwo, RandomGraphsEndIndependentLargerAndWithoutSwapsLeft) {
  std::uint64_t s = 12345;
  const auto next = [&](std::uint32_t n) {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return std::uint32_t((s >> 33) % n);
  };
  int improved = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const std::uint32_t n = 8 + next(40);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (std::uint32_t e = 0; e < 2 * n; ++e) {
      const std::uint32_t a = next(n), b = next(n);
      if (a != b && std::none_of(edges.begin(), edges.end(), [&](const auto& x) { return x == std::pair{a, b} || x == std::pair{b, a}; }))
        edges.emplace_back(a, b);
    }
    const Graph g = graph(n, edges);
    std::vector<char> swappable(n), kept(n, 0);
    for (std::uint32_t i = 0; i < n; ++i) swappable[i] = next(5) != 0;
    for (std::uint32_t i = 0; i < n; ++i)  // a greedy maximal set in a random order
      if (std::none_of(g[i].begin(), g[i].end(), [&](std::uint32_t j) { return kept[j] != 0; })) kept[i] = 1;
    const std::vector<char> before = kept;
    nano::shell::swap_one_for_two(g, swappable, kept);
    for (const auto& [a, b] : edges) EXPECT_FALSE(kept[a] && kept[b]) << "trial " << trial << ": two kept copies clash";
    for (std::uint32_t i = 0; i < n; ++i) {
      if (!swappable[i]) {
        EXPECT_EQ(kept[i], before[i]) << "trial " << trial << ": a protein changed";
      }
      if (!kept[i]) {
        EXPECT_TRUE(std::any_of(g[i].begin(), g[i].end(), [&](std::uint32_t j) { return kept[j] != 0; }))
            << "trial " << trial << ": a dropped copy clashes with nothing kept";
      }
    }
    const auto count = [](const std::vector<char>& k) { return std::count(k.begin(), k.end(), 1); };
    EXPECT_GE(count(kept), count(before));
    improved += count(kept) > count(before);
    EXPECT_FALSE(one_for_two_left(g, swappable, kept)) << "trial " << trial;
  }
  EXPECT_GT(improved, 0) << "no trial had a swap to make, or the test proves nothing";
}
