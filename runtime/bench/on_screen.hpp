#pragma once
// What a frame shows, read from its pixel hits: the molecule copies on screen, the atoms they are
// made of, and the pixels that show an atom (the frame's screen coverage).
#include <cstdint>
#include <span>

#include "shared/camera.h"
#include "shared/package_records.h"

namespace nano::bench {

struct OnScreen {
  std::uint64_t copies = 0;
  std::uint64_t atoms = 0;       // of those copies' molecule types
  std::uint64_t hit_pixels = 0;  // pixels that show an atom
};

// `molecules` is the package's section of molecule types (their atom ranges name a hit's type).
OnScreen on_screen(std::span<const gpu::MoleculeType> molecules, std::span<const gpu::PixelHit> hits);

}  // namespace nano::bench
