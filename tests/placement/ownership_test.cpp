// Watertight ownership: over tessellations of the UV square (jittered grids, axis-aligned grids, fans
// with slivers, tiny and zero-area triangles) every sampled point — random, exactly on edges, exactly
// on vertices, one grid step off an edge — is owned by exactly one triangle. Points are built on the
// 2^-24 grid in integers and converted to float exactly, so "exactly on an edge" holds in float.
// Independent oracle: exact int64 orientation (64-bit C++ integers, not the code under test).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <vector>

#include "shared/ownership.h"
#include "test_util.hpp"

namespace {
using namespace placement_test;
using nano::gpu::own_quantize;
using nano::gpu::own_triangle_owns;

using I2 = std::array<std::int64_t, 2>;
using Tri = std::array<I2, 3>;
constexpr std::int64_t N = std::int64_t(1) << 24;  // the UV square [0,1]² in grid units

glm::vec2 to_uv(const I2& p) { return glm::vec2(float(p[0]) / 16777216.0f, float(p[1]) / 16777216.0f); }

std::int64_t orient64(const I2& a, const I2& b, const I2& p) {
  return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
}
// Closed-triangle containment, exact (either winding; degenerate → false).
bool closed_contains(const Tri& t, const I2& p) {
  std::int64_t area = orient64(t[0], t[1], t[2]);
  if (area == 0) return false;
  for (int i = 0; i < 3; ++i) {
    std::int64_t o = orient64(t[i], t[(i + 1) % 3], p);
    if ((area > 0 && o < 0) || (area < 0 && o > 0)) return false;
  }
  return true;
}
bool open_contains(const Tri& t, const I2& p) {
  std::int64_t area = orient64(t[0], t[1], t[2]);
  if (area == 0) return false;
  for (int i = 0; i < 3; ++i) {
    std::int64_t o = orient64(t[i], t[(i + 1) % 3], p);
    if ((area > 0 && o <= 0) || (area < 0 && o >= 0)) return false;
  }
  return true;
}

std::vector<Tri> grid_tessellation(Rng& rng, int m, std::int64_t jitter) {
  std::vector<I2> v((m + 1) * (m + 1));
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= m; ++i) {
      std::int64_t x = (N / m) * i / 1024 * 1024, y = (N / m) * j / 1024 * 1024;
      if (i == m) x = N;
      if (j == m) y = N;
      if (i > 0 && i < m) x += jitter * rng.integer(-4, 4);
      if (j > 0 && j < m) y += jitter * rng.integer(-4, 4);
      v[j * (m + 1) + i] = {x, y};
    }
  std::vector<Tri> t;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      I2 a = v[j * (m + 1) + i], b = v[j * (m + 1) + i + 1], c = v[(j + 1) * (m + 1) + i + 1],
         d = v[(j + 1) * (m + 1) + i];
      bool flip = rng.integer(0, 1) == 1;
      bool mirror = rng.integer(0, 1) == 1;  // either winding must work
      if (flip) {
        t.push_back(mirror ? Tri{a, c, b} : Tri{a, b, c});
        t.push_back(mirror ? Tri{a, d, c} : Tri{a, c, d});
      } else {
        t.push_back(mirror ? Tri{a, d, b} : Tri{a, b, d});
        t.push_back(mirror ? Tri{b, d, c} : Tri{b, c, d});
      }
    }
  return t;
}

// Fan from centre c to a polygon running along the square's boundary with clusters of points
// 1 grid step apart (slivers with angles ~1e-7) plus zero-area triangles that must own nothing.
std::vector<Tri> fan_tessellation(Rng& rng, I2 c) {
  std::vector<I2> ring;
  auto side = [&](I2 from, I2 to) {
    std::vector<std::int64_t> ks{0};
    for (int k = 0; k < 20; ++k) {
      std::int64_t base = rng.integer(1, int(N / 1024) - 40) * std::int64_t(1024);
      ks.push_back(base);
      ks.push_back(base + 1);  // sliver: 1 grid step apart
      ks.push_back(base + 2);
    }
    std::sort(ks.begin(), ks.end());
    ks.erase(std::unique(ks.begin(), ks.end()), ks.end());
    for (std::int64_t k : ks)
      ring.push_back({from[0] + (to[0] - from[0]) / N * k, from[1] + (to[1] - from[1]) / N * k});
  };
  side({0, 0}, {N, 0});
  side({N, 0}, {N, N});
  side({N, N}, {0, N});
  side({0, N}, {0, 0});
  std::vector<Tri> t;
  for (size_t i = 0; i < ring.size(); ++i) {
    t.push_back({c, ring[i], ring[(i + 1) % ring.size()]});
    if (i % 7 == 0) t.push_back({ring[i], ring[i], c});  // zero area
  }
  return t;
}

struct OwnershipStats {
  long points = 0, on_edge = 0, on_vertex = 0, outside = 0;
};

void check(const std::vector<Tri>& tris, Rng& rng, int samples, OwnershipStats& st) {
  // Quantised float triangles, as the renderer would see them.
  std::vector<std::array<glm::vec2, 3>> ft;
  for (const Tri& t : tris) ft.push_back({to_uv(t[0]), to_uv(t[1]), to_uv(t[2])});
  for (int s = 0; s < samples; ++s) {
    I2 p;
    int kind = s % 5;
    const Tri& t = tris[rng.integer(0, int(tris.size()) - 1)];
    int e = rng.integer(0, 2);
    I2 a = t[e], b = t[(e + 1) % 3];
    if (kind == 0 || (a == b && kind != 2)) {
      p = {rng.integer(0, int(N)), rng.integer(0, int(N))};
    } else if (kind == 2) {
      p = a;  // exactly a vertex
      ++st.on_vertex;
    } else {  // exactly on an edge (points a + k·(b−a)/g with g = gcd), optionally one step off
      std::int64_t dx = b[0] - a[0], dy = b[1] - a[1];
      std::int64_t g = std::gcd(std::abs(dx), std::abs(dy));
      std::int64_t k = std::int64_t(rng.uniform(0, double(g) + 1));
      k = std::min(k, g);
      p = {a[0] + dx / g * k, a[1] + dy / g * k};
      if (kind == 4) {
        p[0] += rng.integer(-1, 1);
        p[1] += rng.integer(-1, 1);
        p[0] = std::clamp<std::int64_t>(p[0], 0, N);
        p[1] = std::clamp<std::int64_t>(p[1], 0, N);
      } else {
        ++st.on_edge;
      }
    }
    ++st.points;
    glm::vec2 uv = to_uv(p);
    ASSERT_EQ(own_quantize(uv), glm::ivec2(int(p[0]), int(p[1])));  // exact round trip
    int owners = 0;
    size_t owner = 0;
    for (size_t i = 0; i < tris.size(); ++i)
      if (own_triangle_owns(ft[i][0], ft[i][1], ft[i][2], uv)) {
        ++owners;
        owner = i;
      }
    // Symbolic perturbation p + (−ε², ε): inside the square iff 0 < x ≤ N and 0 ≤ y < N.
    bool expect_owned = p[0] > 0 && p[0] <= N && p[1] >= 0 && p[1] < N;
    if (!expect_owned) ++st.outside;
    ASSERT_EQ(owners, expect_owned ? 1 : 0) << "point (" << p[0] << ", " << p[1] << ")";
    if (owners == 1) {
      ASSERT_TRUE(closed_contains(tris[owner], p)) << "owner does not even touch the point";
      for (size_t i = 0; i < tris.size(); ++i)
        if (open_contains(tris[i], p)) {
          ASSERT_EQ(i, owner) << "strictly interior point given to another triangle";
        }
    }
  }
}

TEST(Ownership, JitteredGridTessellationExactlyOneOwner) {
  Rng rng(21);
  OwnershipStats st;
  for (int rep = 0; rep < 3; ++rep) check(grid_tessellation(rng, 12, 1024 * 64), rng, 4000, st);
  EXPECT_GT(st.on_edge, 3000);
  EXPECT_GT(st.on_vertex, 1500);
}

TEST(Ownership, AxisAlignedGridTessellationExactlyOneOwner) {
  // Horizontal and vertical shared edges and 6-valent vertices: the tie rule's hardest cases.
  Rng rng(22);
  OwnershipStats st;
  for (int rep = 0; rep < 2; ++rep) check(grid_tessellation(rng, 8, 0), rng, 5000, st);
  EXPECT_GT(st.on_edge, 3000);
}

TEST(Ownership, SliverFanWithZeroAreaTrianglesExactlyOneOwner) {
  Rng rng(23);
  OwnershipStats st;
  check(fan_tessellation(rng, {N / 2 + 3, N / 2 - 5}), rng, 6000, st);
  check(fan_tessellation(rng, {1024, 2048}), rng, 6000, st);  // centre near a corner: tiny triangles
  EXPECT_GT(st.on_edge, 3000);
  EXPECT_GT(st.outside, 0);
}

TEST(Ownership, SharedEdgeBothWindingsAndFloatInputs) {
  // Two triangles sharing a diagonal edge, given with different windings and start vertices.
  glm::vec2 a(0.3f, 0.7f), b(0.9f, 0.1f), c(0.95f, 0.9f), d(0.1f, 0.05f);
  Rng rng(24);
  for (int i = 0; i < 2000; ++i) {
    float t = float(rng.uniform());
    glm::vec2 p = a + t * (b - a);  // near or on the shared edge, in float
    int n = int(own_triangle_owns(a, b, c, p)) + int(own_triangle_owns(d, b, a, p));
    ASSERT_EQ(n, 1);
    n = int(own_triangle_owns(b, c, a, p)) + int(own_triangle_owns(a, d, b, p));
    ASSERT_EQ(n, 1);
  }
}
}  // namespace
