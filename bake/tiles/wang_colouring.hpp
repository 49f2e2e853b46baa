#pragma once
// Which tiles a Wang set has: the colour of each tile's low and high side along every lattice axis.
// Generic over the lattice dimension (2 = squares, 3 = cubes).
//
// complete set: every combination of 2*dims side colours, C^(2*dims) tiles, index = mixed radix.
// variant set ("stochastic subset", K*C^dims tiles): for every combination of the dims incoming
// (low-side) colours there are K tiles; variant k leaves through high-side colours
// (base_a(incoming) + k) mod C, base_a drawn from the seed. A scanline recipe therefore always finds
// a tile (any incoming combination exists), and when K is a multiple of C each face colour is
// uniform and independent of the incoming ones.
#include <array>
#include <cstdint>
#include <vector>

namespace nano::tiles {

using SideColours = std::array<std::array<uint8_t, 2>, 3>;  // [axis][0 = low side, 1 = high side]

struct WangColouring {
  int dims = 2;
  int colours = 2;
  int variants = 0;  // 0: complete set; K > 0: K tiles per incoming colour combination
  std::vector<SideColours> tiles;

  bool complete() const { return variants == 0; }
  uint32_t tile_count() const { return static_cast<uint32_t>(tiles.size()); }
  // Complete sets: the tile with exactly these side colours.
  uint32_t complete_index(const SideColours& c) const;
  // Variant sets: the tile entered through `incoming` (low-side colours) with variant k.
  uint32_t variant_index(const std::array<uint8_t, 3>& incoming, uint32_t k) const;
};

// Throw InputError for dims outside 2..3, colours outside 1..255, or too many tiles (> 2^16).
WangColouring make_complete_colouring(int dims, int colours);
WangColouring make_variant_colouring(int dims, int colours, int variants, uint64_t seed);

}  // namespace nano::tiles
