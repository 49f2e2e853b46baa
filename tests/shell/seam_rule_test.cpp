// The UV-seam rule (shared/seam.h) in the membrane mapping's enumerator, on generated meshes:
//  * seam bits: both triangles of a seam edge carry its edge bit, and only seam edges carry one;
//  * a brute-force sphere-overlap check over every owned molecule of every triangle (its own spatial
//    hash and double distances, no shared code) finds overlapping molecules of different UV charts
//    without the rule and none with it; the keeping side still covers the seam.
// The molecules are single spheres centred on the surface (z = 0), dart-thrown into one periodic
// tile so that a chart's own tiling never overlaps: every overlap is a seam overlap.
#include <cmath>
#include <cstdio>
#include <map>
#include <unordered_map>

#include <gtest/gtest.h>

#include "bake/mesh/mesh_edges.hpp"
#include "shell_test_support.hpp"

using namespace shell_test;
using nano::shell::MembraneMapping;
using nano::shell::OwnedMolecule;
using nano::shell::SeamRule;

namespace {

// Single-atom molecules of radius 6 and 14 Å at their origin; bounding radius = atom radius.
std::vector<nano::tiles::MoleculeType> sphere_types() {
  return {{"small", {{{0.f, 0.f, 0.f}, 6.f}}, 6.f, {0, 0, 1}}, {"large", {{{0.f, 0.f, 0.f}, 14.f}}, 14.f, {0, 0, 1}}};
}

// One 150 Å tile, dense random packing of the two spheres, non-overlapping under the periodic wrap
// (so a 1×1 recipe tiles the plane without overlaps).
nano::tiles::WangSet periodic_sphere_set(const std::vector<nano::tiles::MoleculeType>& types) {
  nano::tiles::WangSet set;
  set.dims = 2;
  set.edge = 150.f;
  set.tiles.resize(1);
  std::uint64_t s = 12345;
  auto next = [&] {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return double(s >> 11) * 0x1.0p-53;
  };
  auto& inst = set.tiles[0].instances;
  for (int attempt = 0; attempt < 20000; ++attempt) {
    const std::uint32_t type = attempt % 4 == 0 ? 1u : 0u;
    const glm::vec3 p(float(next() * 150.0), float(next() * 150.0), 0.f);
    bool free = true;
    for (const auto& o : inst) {
      glm::dvec2 d = glm::dvec2(p) - glm::dvec2(o.position);
      d -= 150.0 * glm::round(d / 150.0);
      if (glm::length(d) < types[type].bounding_radius + types[o.type].bounding_radius + 0.5) free = false;
    }
    if (free) inst.push_back({type, p, glm::quat(1.f, 0.f, 0.f, 0.f)});
  }
  return set;
}

struct Placed {
  dvec3 centre;
  double radius;
  std::uint32_t triangle;
};

std::vector<Placed> enumerate(const MembraneMapping& map, const std::vector<nano::tiles::MoleculeType>& types,
                              SeamRule rule) {
  std::vector<Placed> out;
  for (std::size_t t = 0; t < map.triangle_count(); ++t)
    map.for_each_owned_membrane_molecule(t, [&](const OwnedMolecule& m) {
      out.push_back({dvec3(m.transform.translation), double(types[m.type].atoms[0].radius), std::uint32_t(t)});
    }, rule);
  return out;
}

struct Overlaps {
  std::size_t cross_chart = 0;  // pairs of different charts whose spheres overlap
  std::size_t same_chart = 0;
  double worst = 0;             // deepest cross-chart penetration, Å
};

// Brute force over a hash grid of cell 2·r_max: every pair closer than the sum of radii (1e-3 Å slack
// for float placement).
Overlaps overlaps(const std::vector<Placed>& ms, const std::vector<std::uint32_t>& chart, double r_max) {
  const double cell = 2.0 * r_max;
  auto key = [&](glm::ivec3 c) { return (std::int64_t(c.x) * 73856093) ^ (std::int64_t(c.y) * 19349663) ^ (std::int64_t(c.z) * 83492791); };
  std::unordered_map<std::int64_t, std::vector<std::size_t>> grid;
  for (std::size_t i = 0; i < ms.size(); ++i) grid[key(glm::ivec3(glm::floor(ms[i].centre / cell)))].push_back(i);
  Overlaps o;
  for (std::size_t i = 0; i < ms.size(); ++i) {
    const glm::ivec3 c(glm::floor(ms[i].centre / cell));
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = grid.find(key(c + glm::ivec3(dx, dy, dz)));
          if (it == grid.end()) continue;
          for (std::size_t j : it->second) {
            if (j <= i) continue;
            const double depth = ms[i].radius + ms[j].radius - glm::length(ms[i].centre - ms[j].centre);
            if (!(depth > 1e-3)) continue;
            if (chart[ms[i].triangle] != chart[ms[j].triangle]) {
              ++o.cross_chart;
              o.worst = std::max(o.worst, depth);
            } else {
              ++o.same_chart;
            }
          }
        }
  }
  return o;
}

// Runs the whole check on one mesh; returns the number of dropped molecules.
std::size_t check_mesh(nano::mesh::ProxyMesh mesh, const char* name, std::size_t expected_seam_edges) {
  const auto types = sphere_types();
  const auto set = periodic_sphere_set(types);
  nano::tiles::TilingRecipe recipe;
  recipe.dims = 2;
  recipe.size = {1, 1, 1};
  recipe.cells = {0};
  const MembraneMapping map(mesh, set, recipe, nano::mesh::uv_scale(mesh), types);

  // Seam bits: per edge shared by two faces, count the bits set on it by either face; bits only on
  // a seam edge (UV values differ at an endpoint), one from each face.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::pair<std::uint32_t, int>>> uses;
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      uses[{std::min(a, b), std::max(a, b)}].push_back({t, k});
    }
  const std::vector<std::uint32_t> chart = nano::mesh::uv_charts(mesh, nano::mesh::collect_edges(mesh));
  std::size_t seam_edges = 0;
  for (const auto& [edge, u] : uses) {
    int bits = 0;
    for (const auto& [t, k] : u) bits += (map.seam_edges(t) >> k) & 1u;
    if (u.size() != 2) {
      EXPECT_EQ(bits, 0);
      continue;
    }
    auto uv_of = [&](std::uint32_t t, std::uint32_t v) {
      for (int c = 0; c < 3; ++c)
        if (mesh.triangles[t][c] == v) return map.triangle(t).uv[c];
      return glm::vec2(NAN);
    };
    const bool seam = uv_of(u[0].first, edge.first) != uv_of(u[1].first, edge.first) ||
                      uv_of(u[0].first, edge.second) != uv_of(u[1].first, edge.second);
    EXPECT_EQ(bits, seam ? 2 : 0) << name << " edge " << edge.first << "-" << edge.second;
    seam_edges += seam;
  }
  EXPECT_EQ(seam_edges, expected_seam_edges) << name;

  const auto all = enumerate(map, types, SeamRule::ignore);
  const auto kept = enumerate(map, types, SeamRule::apply);
  const Overlaps before = overlaps(all, chart, 14.0);
  const Overlaps after = overlaps(kept, chart, 14.0);
  std::printf("%s: %zu seam edges; %zu molecules, %zu dropped; cross-chart overlaps %zu (deepest %.2f Å) without the "
              "rule, %zu (deepest %.2f Å) with it; same-chart overlaps %zu / %zu\n",
              name, seam_edges, all.size(), all.size() - kept.size(), before.cross_chart, before.worst,
              after.cross_chart, after.worst, before.same_chart, after.same_chart);
  EXPECT_GT(before.cross_chart, 0u) << "the test needs seam overlaps to remove";
  EXPECT_EQ(after.cross_chart, 0u);
  EXPECT_EQ(map.seam_dropped_count(), all.size() - kept.size());

  // Away from seams nothing is touched: every molecule of a triangle without seam bits is still there.
  std::size_t all_unflagged = 0, kept_unflagged = 0;
  for (const Placed& p : all) all_unflagged += map.seam_edges(p.triangle) == 0;
  for (const Placed& p : kept) kept_unflagged += map.seam_edges(p.triangle) == 0;
  EXPECT_EQ(all_unflagged, kept_unflagged);
  // Each side drops only a band about its own molecules' radius: at most the molecules within the
  // largest radius (14 Å) of a seam edge or twice that of a seam vertex.
  std::size_t near_seam = 0;
  for (const Placed& p : all) {
    const auto& tm = map.triangle(p.triangle);
    bool near = false;
    for (int k = 0; k < 3; ++k)
      near = near || (((map.seam_edges(p.triangle) >> k) & 1u) &&
                      nano::gpu::seam_point_segment_distance(glm::vec3(p.centre), tm.position[k], tm.position[(k + 1) % 3]) < 14.f) ||
             (((map.seam_edges(p.triangle) >> (3 + k)) & 1u) && glm::distance(glm::vec3(p.centre), tm.position[k]) < 28.f);
    near_seam += near;
  }
  EXPECT_LE(all.size() - kept.size(), near_seam);
  return all.size() - kept.size();
}

}  // namespace

TEST(SeamRule, CubeSphereHasNoOverlapsAcrossItsTwelveSeamsAndDropsOnlyNearThem) {
  // n = 8 cells per cube face edge (12·n² triangles): 12 cube edges of 8 mesh edges each are seams.
  const std::size_t dropped = check_mesh(nano::mesh::make_sphere_mesh(12 * 8 * 8, 500.0), "cube-sphere r=500 Å", 12 * 8);
  EXPECT_GT(dropped, 0u);
}

TEST(SeamRule, RedBloodCellBandChartSeamsAreTheSeamBitsEdges) {
  nano::mesh::EvansFungShape shape;
  shape.r0 = 2000.0;
  const auto mesh = nano::mesh::make_rbc_mesh(600, shape);
  // Seam edges counted independently: edges of two faces whose UV indices differ at an endpoint.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::pair<std::uint32_t, std::uint32_t>>> uv_at;
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      const std::uint32_t ua = mesh.uv_triangles[t][k], ub = mesh.uv_triangles[t][(k + 1) % 3];
      uv_at[{std::min(a, b), std::max(a, b)}].push_back(a < b ? std::make_pair(ua, ub) : std::make_pair(ub, ua));
    }
  std::size_t seam_edges = 0;
  for (const auto& [e, u] : uv_at) seam_edges += u.size() == 2 && u[0] != u[1];
  EXPECT_GT(seam_edges, 0u);
  const std::size_t dropped = check_mesh(mesh, "RBC R0=2000 Å", seam_edges);
  EXPECT_GT(dropped, 0u);
}

TEST(SeamRule, SharedHeaderDistanceAndBits) {
  namespace g = nano::gpu;
  const glm::vec3 a(0, 0, 0), b(10, 0, 0), c(0, 10, 0);
  EXPECT_FLOAT_EQ(g::seam_point_segment_distance({5, 3, 4}, a, b), 5.f);   // over the segment
  EXPECT_FLOAT_EQ(g::seam_point_segment_distance({-3, 4, 0}, a, b), 5.f);  // past endpoint a
  EXPECT_FLOAT_EQ(g::seam_point_segment_distance({13, 0, 4}, a, b), 5.f);  // past endpoint b
  EXPECT_FLOAT_EQ(g::seam_point_segment_distance({3, 4, 0}, a, a), 5.f);   // degenerate segment
  // Centre (5, 2, 0): 2 Å from edge 0 (a-b), 3/√2 Å from edge 1 (b-c), 5 Å from edge 2 (c-a).
  const glm::vec3 p(5, 2, 0);
  EXPECT_FALSE(g::seam_drops(0u, a, b, c, p, 2.f));
  EXPECT_TRUE(g::seam_drops(1u, a, b, c, p, 2.5f));    // 2 < 2.5
  EXPECT_FALSE(g::seam_drops(1u, a, b, c, p, 2.f));    // 2 is not < 2: kept on the boundary
  EXPECT_FALSE(g::seam_drops(4u, a, b, c, p, 4.9f));   // 5 ≥ 4.9
  EXPECT_TRUE(g::seam_drops(4u, a, b, c, p, 5.1f));    // 5 < 5.1
  EXPECT_FALSE(g::seam_drops(64u, a, b, c, p, 200.f));  // bits beyond 0-5 mean nothing
  // Corner bits 3-5 keep twice the radius: distance to P0 (a) is √29 ≈ 5.385, to P1 (b) √29, to
  // P2 (c) √89 ≈ 9.434.
  EXPECT_TRUE(g::seam_drops(8u, a, b, c, p, 2.7f));    // √29 < 5.4
  EXPECT_FALSE(g::seam_drops(8u, a, b, c, p, 2.69f));  // √29 ≥ 5.38
  EXPECT_TRUE(g::seam_drops(16u, a, b, c, p, 2.7f));
  EXPECT_FALSE(g::seam_drops(32u, a, b, c, p, 4.71f));  // √89 ≥ 9.42
  EXPECT_TRUE(g::seam_drops(32u, a, b, c, p, 4.72f));   // √89 < 9.44
  const float to_bc = float(std::abs(5.0 + 2.0 - 10.0) / std::sqrt(2.0));  // line x + y = 10
  EXPECT_TRUE(g::seam_drops(2u, a, b, c, p, to_bc + 0.01f));
  EXPECT_FALSE(g::seam_drops(2u, a, b, c, p, to_bc - 0.01f));
}
