#include "format/core_skip.hpp"

#include <algorithm>
#include <cstring>

#include "shaders/shared/core_skip.h"

namespace nano::format {
namespace {

std::uint64_t volume(glm::uvec3 n) { return std::uint64_t{n.x} * n.y * n.z; }

// dst[i] |= src[i] for n bytes, eight at a time.
void or_row(std::uint8_t* dst, const std::uint8_t* src, std::uint64_t n) {
  std::uint64_t i = 0;
  for (; i + 8 <= n; i += 8) {
    std::uint64_t a, b;
    std::memcpy(&a, dst + i, 8);
    std::memcpy(&b, src + i, 8);
    a |= b;
    std::memcpy(dst + i, &a, 8);
  }
  for (; i < n; ++i) dst[i] |= src[i];
}

// out[w] = OR of in[w − 2 .. w] along axis `a` (cells of `in` outside [0, n_in) count as empty): a
// box dilated by one on each side, shifted by one into the widened grid. Other axes keep their size.
// Written in memory order, reading whole rows, so the passes along y and z stream like the x pass.
std::vector<std::uint8_t> dilate_axis(std::span<const std::uint8_t> in, glm::uvec3 n_in, int a, glm::uvec3& n_out) {
  n_out = n_in;
  n_out[a] = n_in[a] + 2;
  std::vector<std::uint8_t> out(volume(n_out), 0);
  const std::uint64_t row = n_in.x;  // x rows of the y and z passes
  std::uint64_t o = 0;
  for (std::uint32_t z = 0; z < n_out.z; ++z)
    for (std::uint32_t y = 0; y < n_out.y; ++y) {
      if (a == 0) {
        const std::uint8_t* src = in.data() + row * (y + std::uint64_t{n_in.y} * z);
        for (std::uint32_t w = 0; w < n_out.x; ++w, ++o)
          out[o] = std::uint8_t((w < n_in.x ? src[w] : 0) | (w >= 1 && w - 1 < n_in.x ? src[w - 1] : 0) |
                                (w >= 2 && w - 2 < n_in.x ? src[w - 2] : 0));
        continue;
      }
      const std::uint32_t w = a == 1 ? y : z;
      for (std::uint32_t b = w < 2 ? 0 : w - 2; b <= w && b < n_in[a]; ++b) {
        const std::uint8_t* src = in.data() + row * (a == 1 ? b + std::uint64_t{n_in.y} * z : y + std::uint64_t{n_in.y} * b);
        or_row(out.data() + o, src, n_out.x);
      }
      o += n_out.x;
    }
  return out;
}

}  // namespace

glm::uvec3 core_skip_cells(const gpu::Compartment& c) { return glm::uvec3(c.grid_dims) + 2u; }
std::uint64_t core_skip_cell_count(const gpu::Compartment& c) { return volume(core_skip_cells(c)); }

std::vector<std::uint8_t> core_live_boxes(const CoreGridRecords& r, std::uint32_t ci) {
  const gpu::Compartment& c = r.compartments[ci];
  const glm::uvec3 dims(c.grid_dims);
  std::vector<std::uint8_t> live(volume(dims), 0);
  const gpu::Recipe& recipe = r.recipes[c.soluble_recipe];
  std::uint32_t largest = 0;
  for (std::uint32_t t = c.soluble_first_tile; t < c.soluble_first_tile + c.soluble_tile_count; ++t)
    largest = std::max(largest, r.tiles3d[t].instance_count);
  const std::uint32_t words_per_box = (largest + 31) / 32;
  std::uint64_t next_mask = c.core_masks.x;  // boundary records ascend by box, as the boxes below
  // Recipes wrap: the cube of box (i, j, k) is recipe cell (i mod X, j mod Y, k mod Z), followed
  // incrementally (a division per box cost more than the rest of the walk on a red blood cell).
  std::uint64_t box = 0;
  for (std::uint32_t k = 0, rk = 0; k < dims.z; ++k, rk = rk + 1 == recipe.dims.z ? 0 : rk + 1)
    for (std::uint32_t j = 0, rj = 0; j < dims.y; ++j, rj = rj + 1 == recipe.dims.y ? 0 : rj + 1) {
      const std::uint32_t* row = r.recipe_indices.data() + recipe.first_index + std::uint64_t{recipe.dims.x} * (rj + std::uint64_t{recipe.dims.y} * rk);
      for (std::uint32_t i = 0, ri = 0; i < dims.x; ++i, ++box, ri = ri + 1 == recipe.dims.x ? 0 : ri + 1) {
        const std::uint8_t occ = r.occupancy[c.grid_dims.w + box];
        if (occ == gpu::NANO_BOX_OUTSIDE) continue;
        const std::uint32_t count = r.tiles3d[row[ri]].instance_count;
        if (count == 0) continue;
        if (occ != gpu::NANO_BOX_BOUNDARY) {
          live[box] = 1;
          continue;
        }
        while (next_mask < std::uint64_t{c.core_masks.x} + c.core_masks.y && r.boundary_boxes[next_mask].box < box) ++next_mask;
        if (next_mask >= std::uint64_t{c.core_masks.x} + c.core_masks.y || r.boundary_boxes[next_mask].box != box) continue;
        const std::uint32_t* words = r.mask_words.data() + r.boundary_boxes[next_mask].first_word;
        for (std::uint32_t w = 0; w < words_per_box && !live[box]; ++w) {
          const std::uint32_t bits = std::min<std::uint32_t>(32, count > 32 * w ? count - 32 * w : 0);
          const std::uint32_t used = bits == 32 ? 0xFFFFFFFFu : (1u << bits) - 1u;
          if (words[w] & used) live[box] = 1;
        }
      }
    }
  return live;
}

std::vector<std::uint8_t> core_skip_levels(glm::uvec3 boxes, std::span<const std::uint8_t> live) {
  // Level 0: a cell is walked when a live box lies within one step of it (separable dilation).
  glm::uvec3 nx, ny, nz;
  std::vector<std::uint8_t> walked = dilate_axis(dilate_axis(dilate_axis(live, boxes, 0, nx), nx, 1, ny), ny, 2, nz);
  // The pyramid: level k + 1 marks a block of 2×2×2 level-k blocks when any of them is marked.
  std::vector<std::vector<std::uint8_t>> marked{std::move(walked)};
  std::vector<glm::uvec3> size{nz};
  while ((size.back().x > 1 || size.back().y > 1 || size.back().z > 1) && marked.size() < gpu::NANO_CORE_SKIP_LEVEL_MAX) {
    const glm::uvec3 f = size.back(), c = (f + 1u) / 2u;
    std::vector<std::uint8_t> up(volume(c), 0);
    for (std::uint32_t z = 0; z < f.z; ++z)
      for (std::uint32_t y = 0; y < f.y; ++y)
        for (std::uint32_t x = 0; x < f.x; ++x)
          if (marked.back()[x + std::uint64_t{f.x} * (y + std::uint64_t{f.y} * z)])
            up[x / 2 + std::uint64_t{c.x} * (y / 2 + std::uint64_t{c.y} * (z / 2))] = 1;
    marked.push_back(std::move(up));
    size.push_back(c);
  }
  // Top down: an unmarked block takes its parent's level when the parent is unmarked too, else its own
  // (k + 1 at level k); a marked block 0.
  std::vector<std::uint8_t> level;
  for (std::size_t k = marked.size(); k-- > 0;) {
    const glm::uvec3 s = size[k];
    std::vector<std::uint8_t> here(volume(s), 0);
    for (std::uint32_t z = 0; z < s.z; ++z)
      for (std::uint32_t y = 0; y < s.y; ++y)
        for (std::uint32_t x = 0; x < s.x; ++x) {
          const std::uint64_t i = x + std::uint64_t{s.x} * (y + std::uint64_t{s.y} * z);
          if (marked[k][i]) continue;
          const std::uint8_t parent =
              level.empty() ? 0 : level[x / 2 + std::uint64_t{size[k + 1].x} * (y / 2 + std::uint64_t{size[k + 1].y} * (z / 2))];
          here[i] = parent != 0 ? parent : std::uint8_t(k + 1);
        }
    level = std::move(here);
  }
  return level;
}

CoreSkipLayout core_skip_layout(std::span<const gpu::Compartment> compartments) {
  CoreSkipLayout layout;
  for (const gpu::Compartment& c : compartments) {
    if (c.soluble_recipe == gpu::NANO_NO_INDEX) {
      layout.first_cell.push_back(kNoCoreGrid);
      continue;
    }
    layout.first_cell.push_back(layout.cells);
    layout.cells += core_skip_cell_count(c);
  }
  return layout;
}

std::vector<std::uint8_t> core_skip_section(const CoreGridRecords& records) {
  const CoreSkipLayout layout = core_skip_layout(records.compartments);
  std::vector<std::uint8_t> bytes((layout.cells + 1) / 2, 0);
  for (std::uint32_t ci = 0; ci < records.compartments.size(); ++ci) {
    if (layout.first_cell[ci] == kNoCoreGrid) continue;
    const gpu::Compartment& c = records.compartments[ci];
    const std::vector<std::uint8_t> levels = core_skip_levels(glm::uvec3(c.grid_dims), core_live_boxes(records, ci));
    for (std::uint64_t i = 0; i < levels.size(); ++i) {
      const std::uint64_t cell = layout.first_cell[ci] + i;
      bytes[cell / 2] |= std::uint8_t(levels[i] << (4 * (cell % 2)));
    }
  }
  return bytes;
}

}  // namespace nano::format
