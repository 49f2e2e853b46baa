#include "bake/tiles/wang_colouring.hpp"

#include "bake/tiles/tile_random.hpp"
#include "common/error.hpp"

#include <string>

namespace nano::tiles {
namespace {

void check(int dims, int colours, double tiles) {
  if (dims != 2 && dims != 3) throw InputError("wang set", "dims", "lattice dimension must be 2 or 3");
  if (colours < 1 || colours > 255) throw InputError("wang set", "colours", "colours per side must be 1..255");
  if (tiles > 65536.0)
    throw InputError("wang set", "colours", "the set would have " + std::to_string(tiles) + " tiles (limit 65536)");
}

double power(int base, int exponent) {
  double p = 1.0;
  for (int i = 0; i < exponent; ++i) p *= base;
  return p;
}

}  // namespace

uint32_t WangColouring::complete_index(const SideColours& c) const {
  uint32_t index = 0;
  for (int a = dims - 1; a >= 0; --a)
    for (int side = 1; side >= 0; --side) index = index * colours + c[a][side];
  return index;
}

uint32_t WangColouring::variant_index(const std::array<uint8_t, 3>& incoming, uint32_t k) const {
  uint32_t combo = 0;
  for (int a = dims - 1; a >= 0; --a) combo = combo * colours + incoming[a];
  return combo * static_cast<uint32_t>(variants) + k;
}

WangColouring make_complete_colouring(int dims, int colours) {
  check(dims, colours, power(colours, 2 * dims));
  WangColouring w{dims, colours, 0, {}};
  const uint32_t n = static_cast<uint32_t>(power(colours, 2 * dims));
  w.tiles.resize(n);
  for (uint32_t index = 0; index < n; ++index) {
    uint32_t rest = index;
    SideColours c{};
    for (int a = 0; a < dims; ++a)
      for (int side = 0; side < 2; ++side) {
        c[a][side] = static_cast<uint8_t>(rest % colours);
        rest /= colours;
      }
    w.tiles[index] = c;
  }
  return w;
}

WangColouring make_variant_colouring(int dims, int colours, int variants, uint64_t seed) {
  if (variants < 1) throw InputError("wang set", "variants", "need at least one tile per incoming colour combination");
  check(dims, colours, power(colours, dims) * variants);
  WangColouring w{dims, colours, variants, {}};
  const uint32_t combos = static_cast<uint32_t>(power(colours, dims));
  SplitMix64 rng(mix64(seed ^ 0x5EEDC0105ull));
  w.tiles.resize(static_cast<size_t>(combos) * variants);
  for (uint32_t combo = 0; combo < combos; ++combo) {
    std::array<uint8_t, 3> incoming{}, base{};
    uint32_t rest = combo;
    for (int a = 0; a < dims; ++a) {
      incoming[a] = static_cast<uint8_t>(rest % colours);
      rest /= colours;
      base[a] = static_cast<uint8_t>(rng.below(static_cast<uint32_t>(colours)));
    }
    for (int k = 0; k < variants; ++k) {
      SideColours c{};
      for (int a = 0; a < dims; ++a) {
        c[a][0] = incoming[a];
        c[a][1] = static_cast<uint8_t>((base[a] + k) % colours);
      }
      w.tiles[w.variant_index(incoming, static_cast<uint32_t>(k))] = c;
    }
  }
  return w;
}

}  // namespace nano::tiles
