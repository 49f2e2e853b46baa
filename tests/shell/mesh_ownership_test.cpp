// Watertight ownership over generated meshes: every molecule of the replicated tiling whose UV lies
// inside a UV chart is yielded by exactly one triangle; the count is checked against a brute-force
// double point-in-triangle test over all triangles. Points within a hair of a chart's outer
// boundary (the seams) may be owned once or not at all; they are counted and bounded.
#include <cstdio>
#include <map>
#include <unordered_map>

#include <gtest/gtest.h>

#include "shell_test_support.hpp"

using namespace shell_test;
using nano::shell::OwnedMolecule;

namespace {

struct Key {
  int a, b;
  unsigned instance;
  bool operator==(const Key&) const = default;
};
struct KeyHash {
  size_t operator()(const Key& k) const {
    return (size_t(unsigned(k.a)) * 73856093u) ^ (size_t(unsigned(k.b)) * 19349663u) ^ (size_t(k.instance) * 83492791u);
  }
};

void check_ownership(const Scene& sc, const char* name) {
  const auto& map = *sc.mapping;
  const double s = map.tile_uv_size(), S = map.tile_edge();
  const double tol = 1e-6;  // UV units: float uv_m is within ~1e-7 of its double value

  // UV triangles in double (the snapped chart) and the chart's outer boundary edges.
  const size_t nt = map.triangle_count();
  std::vector<std::array<dvec2, 3>> tri(nt);
  for (size_t t = 0; t < nt; ++t)
    for (int c = 0; c < 3; ++c) tri[t][c] = dvec2(map.triangle(t).uv[c]);
  std::map<std::pair<unsigned, unsigned>, int> edge_use;
  for (size_t t = 0; t < nt; ++t)
    for (int c = 0; c < 3; ++c) {
      unsigned i = sc.mesh.uv_triangles[t][c], j = sc.mesh.uv_triangles[t][(c + 1) % 3];
      edge_use[{std::min(i, j), std::max(i, j)}] += 1;
    }
  std::vector<std::pair<dvec2, dvec2>> boundary;
  for (const auto& [e, n] : edge_use)
    if (n == 1) boundary.push_back({dvec2(map.snapped_uvs()[e.first]), dvec2(map.snapped_uvs()[e.second])});

  // Candidates: every molecule of every triangle's replication area; owners from the enumerator.
  std::unordered_map<Key, int, KeyHash> owners;
  std::unordered_map<Key, size_t, KeyHash> owner_triangle;
  for (size_t t = 0; t < nt; ++t) {
    const auto& tm = map.triangle(t);
    for (int j = 0; j < tm.extent.y; ++j)
      for (int i = 0; i < tm.extent.x; ++i) {
        const glm::ivec2 cell = tm.origin + glm::ivec2(i, j);
        const size_t n = sc.set.tiles[map.tile_at(cell)].instances.size();
        for (unsigned k = 0; k < n; ++k) owners.try_emplace(Key{cell.x, cell.y, k}, 0);
      }
    map.for_each_owned_membrane_molecule(t, [&](const OwnedMolecule& m) {
      const Key key{m.cell.x, m.cell.y, m.instance};
      ASSERT_TRUE(owners.count(key));
      owners[key] += 1;
      owner_triangle[key] = t;
    }, nano::shell::SeamRule::ignore);  // the partition itself; seam_rule_test checks the drops
  }

  // Triangles bucketed by UV box for the brute force.
  dvec2 lo(1e9), hi(-1e9);
  for (const auto& tr : tri)
    for (const dvec2& p : tr) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
  const int G = 64;
  const dvec2 cell_size = (hi - lo) / double(G) + 1e-12;
  std::vector<std::vector<size_t>> bucket(G * G);
  for (size_t t = 0; t < nt; ++t) {
    const dvec2 a = glm::min(tri[t][0], glm::min(tri[t][1], tri[t][2])) - tol;
    const dvec2 b = glm::max(tri[t][0], glm::max(tri[t][1], tri[t][2])) + tol;
    const glm::ivec2 ia = glm::clamp(glm::ivec2((a - lo) / cell_size), 0, G - 1);
    const glm::ivec2 ib = glm::clamp(glm::ivec2((b - lo) / cell_size), 0, G - 1);
    for (int y = ia.y; y <= ib.y; ++y)
      for (int x = ia.x; x <= ib.x; ++x) bucket[y * G + x].push_back(t);
  }

  size_t interior = 0, edge_cases = 0, seam_cases = 0, seam_owned = 0, outside = 0, owned_total = 0;
  for (const auto& [key, count] : owners) {
    owned_total += count;
    const glm::vec3 p = sc.set.tiles[map.tile_at({key.a, key.b})].instances[key.instance].position;
    const dvec2 uv = dvec2(key.a, key.b) * s + dvec2(p.x, p.y) * (s / S);
    int strict = 0, near = 0;
    size_t strict_t = 0;
    std::vector<size_t> near_t;
    const glm::ivec2 bi = glm::ivec2((uv - lo) / cell_size);
    if (bi.x >= 0 && bi.y >= 0 && bi.x < G && bi.y < G)
      for (size_t t : bucket[bi.y * G + bi.x]) {
        const auto l = barycentric(tri[t][0], tri[t][1], tri[t][2], uv);
        if (!l) continue;
        // Distances to the edge lines in UV: λ_k times the altitude onto edge k.
        const double area2 = std::abs((tri[t][1].x - tri[t][0].x) * (tri[t][2].y - tri[t][0].y) -
                                      (tri[t][1].y - tri[t][0].y) * (tri[t][2].x - tri[t][0].x));
        double dmin = 1e9;
        for (int c = 0; c < 3; ++c)
          dmin = std::min(dmin, (*l)[c] * area2 / glm::length(tri[t][(c + 2) % 3] - tri[t][(c + 1) % 3]));
        if (dmin > tol) { ++strict; strict_t = t; }
        else if (dmin > -tol) { ++near; near_t.push_back(t); }
      }
    bool on_seam = false;
    for (const auto& [a, b] : boundary)
      if (point_segment_distance(uv, a, b) <= tol) { on_seam = true; break; }
    ASSERT_LE(strict, 1) << "UV charts overlap";
    if (strict == 1) {
      ++interior;
      ASSERT_EQ(count, 1) << name << ": interior molecule owned " << count << " times";
      ASSERT_EQ(owner_triangle.at(key), strict_t);
    } else if (on_seam) {
      ++seam_cases;
      seam_owned += count;
      ASSERT_LE(count, 1);
    } else if (near > 0) {
      ++edge_cases;  // on a shared edge or vertex inside the chart: exactly one of the touching triangles
      ASSERT_EQ(count, 1) << name << ": molecule on a shared edge owned " << count << " times";
      ASSERT_NE(std::find(near_t.begin(), near_t.end(), owner_triangle.at(key)), near_t.end());
    } else {
      ++outside;
      ASSERT_EQ(count, 0);
    }
  }
  std::printf("%s: %zu triangles, W×H %d×%d, %zu owned molecules: %zu strictly inside, %zu on shared edges "
              "(owned once), %zu within 1e-6 of a seam (%zu owned), %zu outside the charts\n",
              name, nt, map.replication_area().x, map.replication_area().y, owned_total, interior, edge_cases,
              seam_cases, seam_owned, outside);
  EXPECT_GT(interior, 1000u);
  EXPECT_LE(seam_cases, interior / 1000 + 5);  // seams are lines: a handful of molecules at most
}

// Walking all W×H slots from a triangle's origin (as the shader does) finds no owned molecule beyond
// the triangle's own extent (what the enumerator walks).
void check_walk_range(const Scene& sc) {
  const auto& map = *sc.mapping;
  const glm::ivec2 area = map.replication_area();
  for (size_t t = 0; t < map.triangle_count(); ++t) {
    const auto& tm = map.triangle(t);
    ASSERT_LE(tm.extent.x, area.x);
    ASSERT_LE(tm.extent.y, area.y);
    for (int j = 0; j < area.y; ++j)
      for (int i = 0; i < area.x; ++i) {
        if (i < tm.extent.x && j < tm.extent.y) continue;
        const glm::ivec2 cell = tm.origin + glm::ivec2(i, j);
        const glm::vec2 g = glm::vec2(cell) * map.tile_uv_size();
        for (const auto& in : sc.set.tiles[map.tile_at(cell)].instances)
          ASSERT_FALSE(nano::gpu::own_triangle_owns(tm.uv[0], tm.uv[1], tm.uv[2],
                                                    g + map.s_over_S() * glm::vec2(in.position)));
      }
  }
}

}  // namespace

TEST(MeshOwnership, SphereVirion) {
  const auto sc = sphere_scene();
  check_ownership(*sc, "sphere r=500 Å");
  check_walk_range(*sc);
}

TEST(MeshOwnership, RedBloodCell) {
  const auto sc = rbc_scene();
  check_ownership(*sc, "RBC R0=2000 Å");
  check_walk_range(*sc);
}
