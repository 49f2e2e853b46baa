// Empty-space skipping of the core grid (format/core_skip.hpp, shaders/shared/core_skip.h and
// dda_skip_block of shaders/shared/grid_dda.h) against brute force:
//  - the levels equal their definition, cell by cell (the largest aligned empty block, computed by
//    scanning every block), for random live boxes in grids of odd sizes;
//  - which boxes are live, on the sample scene's grid (a keep-mask keeping nothing is dead, as is a
//    box whose cube is empty);
//  - the skipping walk meets every cell the plain walk meets that has a live box within one step, in
//    the same order, for random, axis-aligned and block-edge rays; and a ray through an empty grid
//    takes O(log n) steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "format/core_skip.hpp"
#include "sample_scene.hpp"
#include "shaders/shared/core_skip.h"
#include "shaders/shared/grid_dda.h"

namespace {
using namespace nano;
using glm::ivec3;
using glm::uvec3;
using glm::vec3;

std::uint64_t index_of(ivec3 p, ivec3 n) { return std::uint64_t(p.x) + std::uint64_t(n.x) * (p.y + std::uint64_t(n.y) * p.z); }
bool inside(ivec3 p, ivec3 n) { return p.x >= 0 && p.y >= 0 && p.z >= 0 && p.x < n.x && p.y < n.y && p.z < n.z; }

std::vector<std::uint8_t> random_live(uvec3 boxes, double density, std::mt19937& rng) {
  std::bernoulli_distribution live(density);
  std::vector<std::uint8_t> v(std::uint64_t(boxes.x) * boxes.y * boxes.z);
  for (auto& b : v) b = live(rng);
  return v;
}

// Cell w of the widened grid is walked when a live box lies within one step of box w − 1.
std::vector<std::uint8_t> walked_by_definition(uvec3 boxes, const std::vector<std::uint8_t>& live) {
  const ivec3 nb(boxes), nc = nb + 2;
  std::vector<std::uint8_t> walked(std::uint64_t(nc.x) * nc.y * nc.z, 0);
  for (int z = 0; z < nc.z; ++z)
    for (int y = 0; y < nc.y; ++y)
      for (int x = 0; x < nc.x; ++x)
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const ivec3 b = ivec3(x, y, z) - 1 + ivec3(dx, dy, dz);
              if (inside(b, nb) && live[index_of(b, nb)]) walked[index_of({x, y, z}, nc)] = 1;
            }
  return walked;
}

// The level by its definition: the largest aligned block (up to the one that covers the grid, and
// at most 2^14 cells) holding the cell and no walked cell.
std::vector<std::uint8_t> levels_by_definition(uvec3 boxes, const std::vector<std::uint8_t>& walked) {
  const ivec3 nc = ivec3(boxes) + 2;
  int top = 0;
  while ((nc.x > (1 << top) || nc.y > (1 << top) || nc.z > (1 << top)) && top < 14) ++top;
  std::vector<std::uint8_t> levels(walked.size(), 0);
  for (int z = 0; z < nc.z; ++z)
    for (int y = 0; y < nc.y; ++y)
      for (int x = 0; x < nc.x; ++x) {
        const ivec3 c(x, y, z);
        for (int k = 0; k <= top; ++k) {
          const ivec3 lo = (c >> k) << k;
          bool empty = true;
          for (int bz = lo.z; bz < std::min(lo.z + (1 << k), nc.z) && empty; ++bz)
            for (int by = lo.y; by < std::min(lo.y + (1 << k), nc.y) && empty; ++by)
              for (int bx = lo.x; bx < std::min(lo.x + (1 << k), nc.x) && empty; ++bx)
                empty = !walked[index_of({bx, by, bz}, nc)];
          if (!empty) break;
          levels[index_of(c, nc)] = std::uint8_t(k + 1);
        }
      }
  return levels;
}

TEST(CoreSkip, LevelsAreTheLargestEmptyAlignedBlock) {
  std::mt19937 rng(7);
  const uvec3 sizes[] = {{1, 1, 1}, {13, 7, 21}, {40, 3, 5}, {30, 30, 30}, {6, 1, 33}};
  for (const uvec3 boxes : sizes)
    for (const double density : {0.0, 0.002, 0.02, 0.3, 1.0}) {
      const auto live = random_live(boxes, density, rng);
      const auto expected = levels_by_definition(boxes, walked_by_definition(boxes, live));
      EXPECT_EQ(format::core_skip_levels(boxes, live), expected)
          << boxes.x << "x" << boxes.y << "x" << boxes.z << " boxes, density " << density;
    }
}

TEST(CoreSkip, LiveBoxesOfTheSampleGrid) {
  format::test::SampleScene s = format::test::make_sample_scene();
  const format::CoreGridRecords records{s.compartments, s.occupancy, s.tiles3d, s.recipes,
                                        s.recipe_indices, s.boundary_boxes, s.mask_words};
  auto live = format::core_live_boxes(records, 0);
  ASSERT_EQ(live.size(), 512u);
  for (std::uint32_t box = 0; box < 512; ++box) {
    // Boxes 200..259 are INSIDE; BOUNDARY box 199 keeps its molecule, BOUNDARY box 260 keeps none.
    const bool expected = (box >= 200 && box < 260) || box == 199;
    EXPECT_EQ(live[box], expected ? 1 : 0) << "box " << box;
  }
  s.tiles3d[0].instance_count = 0;  // an empty cube: nothing to hit anywhere
  live = format::core_live_boxes(records, 0);
  EXPECT_EQ(std::count(live.begin(), live.end(), 1), 0);
  // The section: 10×10×10 widened cells, two a byte.
  EXPECT_EQ(format::core_skip_section(records).size(), 500u);
}

struct WalkResult {
  std::vector<ivec3> walked;  // cells met whose level is 0, in order
  std::vector<float> spans;   // the length in t of each
  int steps = 0;
};

// True if the ray o + t·d, t ∈ [0, t1], passes within 1e-4 cells of `cell` (computed in double).
bool passes_near(ivec3 cell, vec3 o, vec3 d, float t1) {
  double a = 0, b = t1;
  for (int i = 0; i < 3; ++i) {
    const double lo = cell[i] - 1e-4, hi = cell[i] + 1 + 1e-4;
    if (d[i] == 0) {
      if (o[i] < lo || o[i] > hi) return false;
      continue;
    }
    const double x = (lo - o[i]) / d[i], y = (hi - o[i]) / d[i];
    a = std::max(a, std::min(x, y));
    b = std::min(b, std::max(x, y));
  }
  return a <= b;
}

// The core renderer's walk over the widened grid of `levels`, skipping blocks when `skip`.
WalkResult walk(const std::vector<std::uint8_t>& levels, ivec3 nc, vec3 o, vec3 d, float t1, bool skip) {
  WalkResult r;
  gpu::GridDda it;
  gpu::dda_init(it, vec3(0), vec3(1), nc, o, d, 0.0f, t1);
  ivec3 cell;
  float ta;
  while (gpu::dda_current(it, cell, ta)) {
    ++r.steps;
    const std::uint32_t level = levels[index_of(cell, nc)];
    if (level == 0) r.walked.push_back(cell);
    if (level != 0 && skip) {
      const ivec3 lo = gpu::core_skip_block_lo(cell, level);
      gpu::dda_skip_block(it, lo, gpu::core_skip_block_hi(lo, level, nc));
    }
    const float tb = gpu::dda_advance(it);
    if (level == 0) r.spans.push_back(tb - ta);
  }
  return r;
}

TEST(CoreSkip, TheSkippingWalkMeetsEveryCellThePlainWalkMeets) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  long rays = 0, plain_steps = 0, skip_steps = 0;
  const uvec3 sizes[] = {{31, 17, 23}, {64, 64, 8}};
  for (const uvec3 boxes : sizes)
    for (const double density : {0.0005, 0.005, 0.05}) {
      const auto levels = format::core_skip_levels(boxes, random_live(boxes, density, rng));
      const ivec3 nc = ivec3(boxes) + 2;
      const vec3 size(nc);
      for (int k = 0; k < 3000; ++k) {
        vec3 o, d;
        const int kind = k % 4;
        if (kind == 0) {  // random, from outside or inside
          o = vec3(u(rng), u(rng), u(rng)) * size * 1.4f - 0.2f * size;
          d = vec3(u(rng), u(rng), u(rng)) * size - o;
        } else if (kind == 1) {  // along an axis, one or two components ±0
          o = vec3(u(rng), u(rng), u(rng)) * size;
          d = vec3(0.0f);
          d[k % 3] = u(rng) < 0.5f ? -1.0f : 1.0f;
          o[k % 3] = d[k % 3] > 0 ? -1.0f : size[k % 3] + 1.0f;
          if (u(rng) < 0.5f) o[(k + 1) % 3] = std::floor(o[(k + 1) % 3]);  // on a cell plane
        } else if (kind == 2) {  // through block corners and edges (multiples of 8)
          const vec3 a = glm::floor(vec3(u(rng), u(rng), u(rng)) * size / 8.0f) * 8.0f;
          const vec3 b = glm::floor(vec3(u(rng), u(rng), u(rng)) * size / 8.0f) * 8.0f;
          o = a - (b - a);
          d = b - a;
          if (d == vec3(0.0f)) d = vec3(1.0f, 0.0f, 0.0f);
        } else {  // grazing: nearly parallel to a face
          o = vec3(-1.0f, u(rng) * size.y, u(rng) * size.z);
          d = vec3(1.0f, 1e-4f * (u(rng) - 0.5f), 1e-4f * (u(rng) - 0.5f));
        }
        const float t1 = u(rng) < 0.2f ? 0.5f + u(rng) : 1e30f;  // some segments end inside
        const WalkResult plain = walk(levels, nc, o, d, t1, false);
        const WalkResult skipping = walk(levels, nc, o, d, t1, true);
        // Every cell the plain walk crosses (a span of positive length) is met, in the same order; a
        // cell the ray only touches at an edge or corner may be met or not, as by the plain walk
        // itself (grid_dda_test's ambiguous cells), and nothing else is met.
        std::size_t next = 0;
        for (std::size_t c = 0; c < plain.walked.size(); ++c) {
          if (!(plain.spans[c] > 0.0f)) continue;
          const auto at = std::find(skipping.walked.begin() + std::ptrdiff_t(next), skipping.walked.end(), plain.walked[c]);
          ASSERT_NE(at, skipping.walked.end()) << "ray " << k << " misses cell " << c;
          next = std::size_t(at - skipping.walked.begin()) + 1;
        }
        for (const ivec3 c : skipping.walked) ASSERT_TRUE(passes_near(c, o, d, t1)) << "ray " << k;
        ASSERT_LE(skipping.walked.size(), plain.walked.size() + 3) << "ray " << k << " o " << o.x << "," << o.y << "," << o.z << " d " << d.x << "," << d.y << "," << d.z << " t1 " << t1;
        ASSERT_LE(skipping.steps, plain.steps);
        ++rays, plain_steps += plain.steps, skip_steps += skipping.steps;
      }
    }
  std::printf("%ld rays: %.1f steps a ray plain, %.1f skipping\n", rays, double(plain_steps) / rays, double(skip_steps) / rays);
}

TEST(CoreSkip, ARayThroughAnEmptyGridLeavesInLogarithmicSteps) {
  const uvec3 boxes(254, 254, 254);
  std::vector<std::uint8_t> live(std::uint64_t(boxes.x) * boxes.y * boxes.z, 0);
  live[0] = 1;  // one live box in a corner: the grid is not trivially empty
  const auto levels = format::core_skip_levels(boxes, live);
  const ivec3 nc = ivec3(boxes) + 2;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 256.0f);
  int worst = 0;
  for (int k = 0; k < 2000; ++k) {
    const vec3 a(u(rng), u(rng), -1.0f), b(u(rng), u(rng), 257.0f);
    const WalkResult r = walk(levels, nc, a, b - a, 1e30f, true);
    // Rays far from the corner: at most a few blocks of each size on the way (8 sizes up to 256).
    if (glm::length(glm::vec2(a) ) > 64.0f && glm::length(glm::vec2(b)) > 64.0f) worst = std::max(worst, r.steps);
  }
  EXPECT_LE(worst, 4 * 9) << "steps against " << nc.x << " cells an axis";
  std::printf("worst ray across 256^3 cells with one live corner box: %d steps\n", worst);
}

}  // namespace
