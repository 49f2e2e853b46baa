#include "bake/tiles/tiling_recipe.hpp"

#include "bake/tiles/tile_random.hpp"
#include "common/error.hpp"

namespace nano::tiles {
namespace {

constexpr uint32_t kVariantTag = 7;

uint8_t face_colour(const WangColouring& set, const std::array<int, 3>& size, bool periodic, uint64_t seed,
                    std::array<int, 3> lattice_point, int axis) {
  if (periodic)
    for (int a = 0; a < 3; ++a) lattice_point[a] = ((lattice_point[a] % size[a]) + size[a]) % size[a];
  const uint64_t h = lattice_hash(seed, lattice_point[0], lattice_point[1], lattice_point[2], static_cast<uint32_t>(axis));
  return static_cast<uint8_t>((h >> 16) % static_cast<uint64_t>(set.colours));
}

}  // namespace

TilingRecipe make_tiling_recipe(const WangColouring& set, std::array<int, 3> size, uint64_t seed, bool periodic) {
  if (set.dims == 2) size[2] = 1;
  double total = 1.0;
  for (int a = 0; a < 3; ++a) {
    if (size[a] < 1 || size[a] > (1 << 20))
      throw InputError("tiling recipe", "size", "cells per axis must be 1..1048576");
    total *= size[a];
  }
  if (total > double(1u << 30)) throw InputError("tiling recipe", "size", "more than 2^30 cells");
  if (periodic && !set.complete())
    throw InputError("tiling recipe", "periodic", "a periodic recipe needs a complete Wang set (variants = 0)");
  if (set.tiles.empty()) throw InputError("tiling recipe", "set", "the Wang set has no tiles");

  TilingRecipe r{set.dims, size, periodic, {}};
  r.cells.resize(static_cast<size_t>(total));
  for (int k = 0; k < size[2]; ++k)
    for (int j = 0; j < size[1]; ++j)
      for (int i = 0; i < size[0]; ++i) {
        const std::array<int, 3> cell{i, j, k};
        const size_t index = (static_cast<size_t>(k) * size[1] + j) * size[0] + i;
        if (set.complete()) {
          SideColours c{};
          for (int a = 0; a < set.dims; ++a) {
            std::array<int, 3> high = cell;
            ++high[a];
            c[a][0] = face_colour(set, size, periodic, seed, cell, a);
            c[a][1] = face_colour(set, size, periodic, seed, high, a);
          }
          r.cells[index] = set.complete_index(c);
        } else {
          std::array<uint8_t, 3> incoming{};
          for (int a = 0; a < set.dims; ++a) {
            if (cell[a] == 0) {
              incoming[a] = face_colour(set, size, false, seed, cell, a);
            } else {
              std::array<int, 3> low = cell;
              --low[a];
              incoming[a] = set.tiles[r.at(low[0], low[1], low[2])][a][1];
            }
          }
          const uint64_t h = lattice_hash(seed, i, j, k, kVariantTag);
          r.cells[index] = set.variant_index(incoming, static_cast<uint32_t>((h >> 16) % set.variants));
        }
      }
  return r;
}

}  // namespace nano::tiles
