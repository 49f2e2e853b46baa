// Slab test and 3D-DDA vs brute force in double: for thousands of rays (random, axis-aligned with ±0
// components, through lattice corners and edges, origins on cell boundaries, segments ending inside)
// the visited cells must be exactly the cells the segment crosses, in order, up to cells the segment
// passes within δ = 1e-6 (grid units) of (counted as ambiguous).
#include <gtest/gtest.h>

#include <set>
#include <tuple>
#include <vector>

#include "shared/grid_dda.h"
#include "test_util.hpp"

namespace {
using namespace placement_test;
namespace g = nano::gpu;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Interval of t ∈ [t0, t1] where o + t d is in the closed box [lo, hi] (double). Empty: a > b.
void box_interval(dvec3 lo, dvec3 hi, dvec3 o, dvec3 d, double t0, double t1, double& a, double& b) {
  a = t0;
  b = t1;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0) {
      if (o[i] < lo[i] || o[i] > hi[i]) { a = kInfinity; b = -kInfinity; return; }
      continue;
    }
    double x = (lo[i] - o[i]) / d[i], y = (hi[i] - o[i]) / d[i];
    a = std::max(a, std::min(x, y));
    b = std::min(b, std::max(x, y));
  }
}

struct Grid {
  glm::vec3 gmin, cs;
  glm::ivec3 res;
};

struct DdaStats {
  long rays = 0, cells = 0, ambiguous = 0, hits = 0;
};

void check_ray(const Grid& gr, glm::vec3 o, glm::vec3 d, float t0, float t1, DdaStats& st) {
  ++st.rays;
  g::GridDda it;
  g::dda_init(it, gr.gmin, gr.cs, gr.res, o, d, t0, t1);
  std::vector<glm::ivec3> seq;
  std::vector<std::pair<float, float>> spans;
  glm::ivec3 cell;
  float ta, tb;
  while (g::dda_next(it, cell, ta, tb)) {
    ASSERT_FALSE(std::isnan(ta) || std::isnan(tb));
    seq.push_back(cell);
    spans.push_back({ta, tb});
    ASSERT_LE(int(seq.size()), gr.res.x + gr.res.y + gr.res.z + 3);
  }
  // Oracle, in grid units so δ is relative to a cell.
  dvec3 og = (D(o) - D(gr.gmin)) / D(gr.cs), dg = D(d) / D(gr.cs);
  const double delta = 1e-6;
  struct OC { glm::ivec3 c; double a; };
  std::vector<OC> solid;
  std::set<std::tuple<int, int, int>> possible;
  double cover_a = kInfinity, cover_b = -kInfinity;
  for (int z = 0; z < gr.res.z; ++z)
    for (int y = 0; y < gr.res.y; ++y)
      for (int x = 0; x < gr.res.x; ++x) {
        dvec3 lo(x, y, z), hi(x + 1, y + 1, z + 1);
        double a, b;
        box_interval(lo + delta, hi - delta, og, dg, t0, t1, a, b);
        if (a < b) solid.push_back({{x, y, z}, a});
        box_interval(lo - delta, hi + delta, og, dg, t0, t1, a, b);
        if (a <= b) {
          possible.insert({x, y, z});
          double a0, b0;
          box_interval(lo, hi, og, dg, t0, t1, a0, b0);
          if (a0 <= b0) cover_a = std::min(cover_a, a0), cover_b = std::max(cover_b, b0);
        }
      }
  std::sort(solid.begin(), solid.end(), [](const OC& l, const OC& r) { return l.a < r.a; });
  std::set<std::tuple<int, int, int>> seen;
  for (size_t k = 0; k < seq.size(); ++k) {
    auto key = std::make_tuple(seq[k].x, seq[k].y, seq[k].z);
    ASSERT_TRUE(seen.insert(key).second) << "cell visited twice";
    ASSERT_TRUE(possible.count(key)) << "visited a cell the segment does not touch: " << seq[k].x << ","
                                     << seq[k].y << "," << seq[k].z;
    if (k > 0) {  // 6-connected and contiguous in t
      glm::ivec3 s = glm::abs(seq[k] - seq[k - 1]);
      ASSERT_EQ(s.x + s.y + s.z, 1);
      ASSERT_EQ(spans[k].first, spans[k - 1].second);
    }
    ASSERT_LE(spans[k].first, spans[k].second);
  }
  // every solid cell visited, in ray order
  size_t pos = 0;
  for (const OC& s : solid) {
    auto key = std::make_tuple(s.c.x, s.c.y, s.c.z);
    ASSERT_TRUE(seen.count(key)) << "missed cell " << s.c.x << "," << s.c.y << "," << s.c.z;
    size_t at = 0;
    while (seq[at] != s.c) ++at;
    ASSERT_GE(at, pos) << "out of order";
    pos = at;
  }
  st.cells += long(seq.size());
  st.ambiguous += long(seq.size() - solid.size());
  if (!seq.empty()) {
    ++st.hits;
    // the spans cover the segment's part inside the grid
    double tol = 1e-5 * (std::abs(cover_b) + 1.0 / glm::length(dg));
    ASSERT_NEAR(spans.front().first, cover_a, tol);
    ASSERT_NEAR(spans.back().second, cover_b, tol);
  } else if (cover_a < cover_b) {
    // only a δ-thin touch may be skipped
    ASSERT_LT((cover_b - cover_a) * glm::length(dg), 1e-5);
  }
}

Grid random_grid(Rng& rng, bool exact) {
  Grid gr;
  gr.res = glm::ivec3(rng.integer(1, 9), rng.integer(1, 9), rng.integer(1, 9));
  if (exact) {  // power-of-two cells and integer origin: grid units are exact in float
    gr.cs = glm::vec3(float(1 << rng.integer(0, 8)), float(1 << rng.integer(0, 8)), float(1 << rng.integer(0, 8)));
    gr.gmin = glm::vec3(float(rng.integer(-500, 500)), float(rng.integer(-500, 500)), float(rng.integer(-500, 500)));
  } else {
    gr.cs = glm::vec3(float(rng.uniform(10, 300)), float(rng.uniform(10, 300)), float(rng.uniform(10, 300)));
    gr.gmin = rng.in_box(-1000, 1000);
  }
  return gr;
}

glm::vec3 grid_point(const Grid& gr, dvec3 u) { return glm::vec3(D(gr.gmin) + u * D(gr.cs)); }

TEST(GridDda, RandomRaysMatchBruteForce) {
  Rng rng(61);
  DdaStats st;
  for (int i = 0; i < 6000; ++i) {
    Grid gr = random_grid(rng, i % 2 == 0);
    dvec3 r(gr.res);
    glm::vec3 o = grid_point(gr, dvec3(rng.uniform(-0.5, 1.5), rng.uniform(-0.5, 1.5), rng.uniform(-0.5, 1.5)) * r);
    glm::vec3 tgt = grid_point(gr, dvec3(rng.uniform(), rng.uniform(), rng.uniform()) * r);
    glm::vec3 d = (tgt - o) * float(std::pow(10.0, rng.uniform(-2, 2)));
    if (glm::length(d) == 0) continue;
    float t0 = i % 3 == 0 ? float(rng.uniform(-1, 1) * std::pow(10.0, -rng.uniform(-2, 2))) : 0.0f;
    float t1 = i % 4 == 0 ? float(rng.uniform(0, 2) / std::pow(10.0, rng.uniform(-2, 2))) : 1e30f;
    check_ray(gr, o, d, t0, t1, st);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(st.hits, 4000);
  std::printf("dda random: %ld rays, %ld cells, %ld ambiguous\n", st.rays, st.cells, st.ambiguous);
}

TEST(GridDda, AxisAlignedRaysWithSignedZerosAndOriginsOnBoundaries) {
  Rng rng(62);
  DdaStats st;
  for (int i = 0; i < 6000; ++i) {
    Grid gr = random_grid(rng, true);
    dvec3 u;
    for (int a = 0; a < 3; ++a) {
      // on a cell boundary (including the grid's outer faces) half of the time
      u[a] = rng.integer(0, 1) ? double(rng.integer(0, gr.res[a])) : rng.uniform(-0.3, gr.res[a] + 0.3);
    }
    glm::vec3 o = grid_point(gr, u);
    int axis = rng.integer(0, 2);
    glm::vec3 d(rng.integer(0, 1) ? 0.0f : -0.0f, rng.integer(0, 1) ? 0.0f : -0.0f, rng.integer(0, 1) ? 0.0f : -0.0f);
    d[axis] = (rng.integer(0, 1) ? 1.0f : -1.0f) * float(std::pow(2.0, rng.integer(-4, 4)));
    if (i % 3 == 0) {  // two non-zero components
      int b = (axis + 1) % 3;
      d[b] = (rng.integer(0, 1) ? 1.0f : -1.0f) * float(std::pow(2.0, rng.integer(-4, 4)));
    }
    o[axis] = grid_point(gr, dvec3(-1.0))[axis] * (d[axis] > 0 ? 1.0f : 1.0f);
    if (d[axis] < 0) o[axis] = grid_point(gr, dvec3(gr.res) + 1.0)[axis];
    if (i % 5 == 0) o = grid_point(gr, u);  // origin inside / on a boundary
    check_ray(gr, o, d, 0.0f, 1e30f, st);
    if (HasFatalFailure()) return;
  }
  std::printf("dda axis-aligned: %ld rays, %ld cells, %ld ambiguous\n", st.rays, st.cells, st.ambiguous);
}

TEST(GridDda, RaysThroughLatticeCornersAndEdges) {
  Rng rng(63);
  DdaStats st;
  for (int i = 0; i < 6000; ++i) {
    Grid gr = random_grid(rng, true);
    // a lattice corner (or edge point) inside the grid and a direction with small integer ratios, so
    // the ray meets several corners/edges exactly
    dvec3 corner(rng.integer(0, gr.res.x), rng.integer(0, gr.res.y), rng.integer(0, gr.res.z));
    if (i % 2 == 1) corner.z += rng.uniform();  // on an edge parallel to z
    dvec3 dir(rng.integer(-2, 2), rng.integer(-2, 2), rng.integer(-2, 2));
    if (dir == dvec3(0)) dir.x = 1;
    glm::vec3 o = grid_point(gr, corner - dir * double(rng.integer(1, 12)));
    glm::vec3 d = glm::vec3(dir * D(gr.cs) * 0.25);
    check_ray(gr, o, d, 0.0f, 1e30f, st);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(st.ambiguous, 0);
  std::printf("dda corners/edges: %ld rays, %ld cells, %ld ambiguous (zero-length corner/edge touches)\n",
              st.rays, st.cells, st.ambiguous);
}

TEST(GridDda, DegenerateInputs) {
  Grid gr{glm::vec3(0), glm::vec3(1), glm::ivec3(4)};
  g::GridDda it;
  glm::ivec3 c;
  float a, b;
  g::dda_init(it, gr.gmin, gr.cs, glm::ivec3(0, 4, 4), glm::vec3(-1, 0.5f, 0.5f), glm::vec3(1, 0, 0), 0, 10);
  EXPECT_FALSE(g::dda_next(it, c, a, b));  // empty grid
  g::dda_init(it, gr.gmin, gr.cs, gr.res, glm::vec3(-1, 0.5f, 0.5f), glm::vec3(0), 0, 10);
  EXPECT_FALSE(g::dda_next(it, c, a, b));  // zero direction outside
  g::dda_init(it, gr.gmin, gr.cs, gr.res, glm::vec3(-1, 0.5f, 0.5f), glm::vec3(-1, 0, 0), 0, 10);
  EXPECT_FALSE(g::dda_next(it, c, a, b));  // pointing away
  g::dda_init(it, gr.gmin, gr.cs, gr.res, glm::vec3(-1, 0.5f, 0.5f), glm::vec3(1, 0, 0), 0, 0.5f);
  EXPECT_FALSE(g::dda_next(it, c, a, b));  // segment ends before the grid
}

TEST(AabbSlab, NeverNaNAndMatchesDouble) {
  Rng rng(64);
  const float z = 0.0f, nz = -0.0f;
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    glm::vec3 lo = rng.in_box(-10, 0), hi = lo + rng.in_box(0.5, 10);
    glm::vec3 o = rng.in_box(-15, 15);
    glm::vec3 aim = lo + (hi - lo) * glm::vec3(float(rng.uniform(-0.2, 1.2)), float(rng.uniform(-0.2, 1.2)), float(rng.uniform(-0.2, 1.2)));
    glm::vec3 d = glm::normalize(aim - o);
    for (int a = 0; a < 3; ++a) {
      int k = rng.integer(0, 5);
      if (k == 0) d[a] = z;
      if (k == 1) d[a] = nz;
      if (k == 2) o[a] = lo[a];  // origin on a slab (0·∞ in a naive test)
      if (k == 3) o[a] = hi[a];
    }
    float tn, tf;
    bool got = g::aabb_intersect(lo, hi, o, d, 0.0f, 1e30f, tn, tf);
    if (got) {
      ASSERT_FALSE(std::isnan(tn) || std::isnan(tf));
    }
    double a, b;
    box_interval(D(lo), D(hi), D(o), D(d), 0.0, 1e30, a, b);
    double ea, eb, sa, sb;  // grown / shrunk by 1e-5
    box_interval(D(lo) - 1e-5, D(hi) + 1e-5, D(o), D(d), 0.0, 1e30, ea, eb);
    box_interval(D(lo) + 1e-5, D(hi) - 1e-5, D(o), D(d), 0.0, 1e30, sa, sb);
    if (sa < sb) {
      ASSERT_TRUE(got);
      ASSERT_NEAR(tn, a, 1e-5 * (1 + std::abs(a)));
      ASSERT_NEAR(tf, b, 1e-5 * (1 + std::abs(b)));
      ASSERT_GE(tf, b);  // widened, never short
      ++hits;
    } else if (!(ea <= eb)) {
      ASSERT_FALSE(got);
    }
  }
  EXPECT_GT(hits, 1500);
  // origin on the slab, direction −0 along it: inside the closed slab for all t
  float tn, tf;
  ASSERT_TRUE(g::aabb_intersect(glm::vec3(0), glm::vec3(1), glm::vec3(0, 0.5f, 0.5f), glm::vec3(nz, 1, 0), 0, 10, tn, tf));
  EXPECT_EQ(tn, 0.0f);
  EXPECT_GE(tf, 0.5f);
}
}  // namespace
