#include "runtime/bench/on_screen.hpp"

#include <set>

namespace nano::bench {

OnScreen on_screen(std::span<const gpu::MoleculeType> molecules, std::span<const gpu::PixelHit> hits) {
  std::set<std::uint64_t> copies;
  OnScreen seen;
  for (const gpu::PixelHit& h : hits) {
    if (h.atom == gpu::kNoHit) continue;
    ++seen.hit_pixels;
    const std::uint64_t number = std::uint64_t(h.copy_number_lo) | (std::uint64_t(h.copy_number_hi) << 32);
    if (!copies.insert(number).second) continue;
    for (const gpu::MoleculeType& m : molecules)
      if (h.atom >= m.first_atom && h.atom - m.first_atom < m.atom_count) seen.atoms += m.atom_count;
  }
  seen.copies = copies.size();
  return seen;
}

}  // namespace nano::bench
