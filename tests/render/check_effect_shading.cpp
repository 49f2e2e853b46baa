// Ambient occlusion and shadows may only darken: with the same camera, the frame with the effects
// must hit the very same atoms (they change shading, not visibility), no hit pixel may be brighter
// than without them (occlusion and shadow only remove light), and some must be darker.
// With LESS_THAN.png (a frame of the same view shaded otherwise): the mean over hit pixels of the
// luminance kept (shaded / plain) must be at least 0.05 below that frame's: AO whose radius follows
// the pixel must carry more than one measured in Å when seen from afar.
// Usage: check_effect_shading PLAIN.png PLAIN.ids SHADED.png SHADED.ids MIN_DARKER_FRACTION [LESS_THAN.png]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "tests/render/rendered_frame.hpp"

namespace {
int luminance(std::uint32_t rgba) { return int(rgba & 255u) + int((rgba >> 8) & 255u) + int((rgba >> 16) & 255u); }
}  // namespace

int main(int argc, char** argv) {
  if (argc != 6 && argc != 7)
    return std::fprintf(stderr, "usage: check_effect_shading PLAIN.png PLAIN.ids SHADED.png SHADED.ids MIN_FRACTION [LESS_THAN.png]\n"), 2;
  try {
    using nano::render::test::read_rendered_frame;
    const auto plain_frame = read_rendered_frame(argv[1], argv[2]);
    const auto shaded_frame = read_rendered_frame(argv[3], argv[4]);
    if (!plain_frame.same_size(shaded_frame)) return std::fprintf(stderr, "sizes differ\n"), 1;
    const auto& plain = plain_frame.rgba;
    const auto& plain_ids = plain_frame.ids;
    const auto& shaded = shaded_frame.rgba;
    const auto& shaded_ids = shaded_frame.ids;
    std::vector<std::uint32_t> other;
    if (argc == 7) {
      std::uint32_t ow = 0, oh = 0;
      other = nano::render::read_png(argv[6], ow, oh);
      if (ow != plain_frame.width || oh != plain_frame.height) return std::fprintf(stderr, "%s differs in size\n", argv[6]), 1;
    }
    double kept = 0, other_kept = 0;
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
      kept += double(luminance(shaded[i])) / std::max(1, luminance(plain[i]));
      if (!other.empty()) other_kept += double(luminance(other[i])) / std::max(1, luminance(plain[i]));
      const int d = luminance(shaded[i]) - luminance(plain[i]);
      if (d > 3) ++brighter;  // 1 unit per channel of rounding
      if (d < -3) ++darker;
    }
    const double fraction = hit ? double(darker) / double(hit) : 0.0;
    std::printf("%zu hit pixels: %zu darker (%.3f), %zu brighter or changed background, %zu with another hit\n", hit, darker,
                fraction, brighter, other_hit);
    if (other_hit != 0 || brighter != 0 || hit == 0 || fraction < std::atof(argv[5])) return 1;
    if (!other.empty()) {
      std::printf("luminance kept: %.3f, against %.3f in %s\n", kept / double(hit), other_kept / double(hit), argv[6]);
      if (!(kept / double(hit) <= other_kept / double(hit) - 0.05)) return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
