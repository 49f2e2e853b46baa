// Empty-space skipping in the core grid (section "core_skip", format 2.7): the cells the renderer's
// DDA walks are those of the core grid widened by one box on every side (cell w ↔ box w − 1), and a
// cell is walked box by box only when a box within one step of it holds a copy a ray can hit (a
// "live" box: not OUTSIDE, its cube not empty, a BOUNDARY box's keep-mask keeping one). Every other
// cell carries a skip level L ≥ 1: the aligned block of 2^(L−1) cells per axis that contains it has
// no such cell, so the walk leaves the whole block in one step (grid_dda.h, dda_skip_block).
// A ray that meets nothing thus crosses O(log n) blocks instead of n cells. GLSL 460 and C++20/GLM.
#ifndef NANO_CORE_SKIP_H
#define NANO_CORE_SKIP_H
#include "shared/glsl_cpp.h"

NANO_BEGIN

// Levels are 4-bit values, two cells a byte (low nibble first), 8 cells a 32-bit word.
NANO_CONST uint NANO_CORE_SKIP_LEVEL_MAX = 15u;

// The skip level of cell `index` (counted over every grid of the section) from its 32-bit word.
NANO_FN uint core_skip_level_in_word(uint word, uint index) { return (word >> (4u * (index & 7u))) & 0xFu; }

// Corners (inclusive) of the block of skip level `level` ≥ 1 that holds `cell`, in a grid of `res` cells.
NANO_FN ivec3 core_skip_block_lo(NANO_IN(ivec3) cell, uint level) {
  int k = int(level) - 1;
  return (cell >> k) << k;
}
NANO_FN ivec3 core_skip_block_hi(NANO_IN(ivec3) block_lo, uint level, NANO_IN(ivec3) res) {
  return min(block_lo + ivec3((1 << (int(level) - 1)) - 1), res - ivec3(1));
}

NANO_END
#endif
