#pragma once
// Tiling recipes: which tile of a Wang set sits at each lattice cell.
//
// Complete sets, edge-first: the colour of every lattice face is hash(i, j, k, axis, seed) mod C and
// the cell takes the tile with its faces' colours: O(1) per cell, independent of visiting order,
// and periodic when face indices wrap modulo the size (a wrapped UV direction tiles seamlessly).
// Variant sets, scanline: cells in x-fastest order; a cell's low-side colours are its low
// neighbours' high-side colours (hashed faces on the low border), its variant is hash(cell) mod K,
// and a matching tile always exists. Periodic recipes need a complete set (InputError otherwise).
#include "bake/tiles/wang_colouring.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace nano::tiles {

struct TilingRecipe {
  int dims = 2;
  std::array<int, 3> size{1, 1, 1};  // cells per axis; size[2] == 1 for 2D recipes
  bool periodic = false;
  std::vector<uint32_t> cells;  // x fastest, then y, then z

  uint32_t at(int i, int j, int k = 0) const {
    return cells[(static_cast<size_t>(k) * size[1] + j) * size[0] + i];
  }
};

// Throws InputError for non-positive sizes, more than 2^20 cells per axis or 2^30 cells in all,
// or a periodic recipe over a variant set.
TilingRecipe make_tiling_recipe(const WangColouring& set, std::array<int, 3> size, uint64_t seed,
                                bool periodic);

}  // namespace nano::tiles
