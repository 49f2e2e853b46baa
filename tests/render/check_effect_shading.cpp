// Ambient occlusion and shadows may only darken: with the same camera, the frame with the effects
// must hit the very same atoms (they change shading, not visibility), no hit pixel may be brighter
// than without them (occlusion and shadow only remove light), and some must be darker.
// Usage: check_effect_shading PLAIN.png PLAIN.ids SHADED.png SHADED.ids MIN_DARKER_FRACTION
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "runtime/render/image_io.hpp"

namespace {
int luminance(std::uint32_t rgba) { return int(rgba & 255u) + int((rgba >> 8) & 255u) + int((rgba >> 16) & 255u); }
}  // namespace

int main(int argc, char** argv) {
  if (argc != 6) return std::fprintf(stderr, "usage: check_effect_shading PLAIN.png PLAIN.ids SHADED.png SHADED.ids MIN_FRACTION\n"), 2;
  try {
    std::uint32_t w = 0, h = 0, w2 = 0, h2 = 0, iw = 0, ih = 0, iw2 = 0, ih2 = 0;
    const auto plain = nano::render::read_png(argv[1], w, h);
    const auto plain_ids = nano::render::read_ids(argv[2], iw, ih);
    const auto shaded = nano::render::read_png(argv[3], w2, h2);
    const auto shaded_ids = nano::render::read_ids(argv[4], iw2, ih2);
    if (w != w2 || h != h2 || iw != w || ih != h || iw2 != w || ih2 != h) return std::fprintf(stderr, "sizes differ\n"), 1;
    std::size_t hit = 0, darker = 0, brighter = 0, other_hit = 0;
    for (std::size_t i = 0; i < plain.size(); ++i) {
      const auto& a = plain_ids[i];
      const auto& b = shaded_ids[i];
      if (a.atom != b.atom || a.copy_number_lo != b.copy_number_lo || a.copy_number_hi != b.copy_number_hi ||
          !(a.depth == b.depth || std::abs(a.depth - b.depth) <= 1e-3f * std::max(1.0f, a.depth))) {
        ++other_hit;
        continue;
      }
      if (a.atom == nano::gpu::kNoHit) {
        if (plain[i] != shaded[i]) ++brighter;  // the background must not change either
        continue;
      }
      ++hit;
      const int d = luminance(shaded[i]) - luminance(plain[i]);
      if (d > 3) ++brighter;  // 1 unit per channel of rounding
      if (d < -3) ++darker;
    }
    const double fraction = hit ? double(darker) / double(hit) : 0.0;
    std::printf("%zu hit pixels: %zu darker (%.3f), %zu brighter or changed background, %zu with another hit\n", hit, darker,
                fraction, brighter, other_hit);
    if (other_hit != 0 || brighter != 0 || hit == 0 || fraction < std::atof(argv[5])) return 1;
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
