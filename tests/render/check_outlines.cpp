// Outlines lie exactly on the discontinuities of the ids image. With the same camera, a frame with
// outlines must show the outline colour on every pixel the rule below selects from its own ids and
// depths, and exactly the plain frame's colour everywhere else; the hits must not change.
// The rule, written here from docs/effects.md and not from the shader: a pixel is outlined when a
// pixel within WIDTH (Chebyshev distance, inside the image) was hit, is nearer, and shows another
// molecule copy, or the same copy nearer by more than CREASE Å; the background is infinitely far.
// Usage: check_outlines PLAIN.png PLAIN.ids OUTLINED.png OUTLINED.ids WIDTH CREASE RGBA_HEX
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

#include "tests/render/rendered_frame.hpp"

namespace {

using nano::gpu::PixelHit;

bool same_hit(const PixelHit& a, const PixelHit& b) {
  return a.atom == b.atom && a.copy_number_lo == b.copy_number_lo && a.copy_number_hi == b.copy_number_hi &&
         (a.depth == b.depth || (std::isinf(a.depth) && std::isinf(b.depth)));
}

std::vector<bool> expected_outline(const std::vector<PixelHit>& ids, int w, int h, int width, float crease) {
  const auto depth = [&](const PixelHit& p) {
    return p.atom == nano::gpu::kNoHit ? std::numeric_limits<float>::infinity() : p.depth;
  };
  std::vector<bool> out(ids.size(), false);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const PixelHit& here = ids[std::size_t(y) * w + x];
      for (int qy = std::max(0, y - width); qy <= std::min(h - 1, y + width) && !out[std::size_t(y) * w + x]; ++qy)
        for (int qx = std::max(0, x - width); qx <= std::min(w - 1, x + width); ++qx) {
          const PixelHit& there = ids[std::size_t(qy) * w + qx];
          if (there.atom == nano::gpu::kNoHit || !(depth(there) < depth(here))) continue;
          const bool same_copy = here.atom != nano::gpu::kNoHit && here.copy_number_lo == there.copy_number_lo &&
                                 here.copy_number_hi == there.copy_number_hi;
          if (!same_copy || depth(here) - depth(there) > crease) {
            out[std::size_t(y) * w + x] = true;
            break;
          }
        }
    }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 8)
    return std::fprintf(stderr, "usage: check_outlines PLAIN.png PLAIN.ids OUTLINED.png OUTLINED.ids WIDTH CREASE RGBA_HEX\n"), 2;
  try {
    using nano::render::test::read_rendered_frame;
    const auto plain_frame = read_rendered_frame(argv[1], argv[2]);
    const auto outlined_frame = read_rendered_frame(argv[3], argv[4]);
    if (!plain_frame.same_size(outlined_frame)) return std::fprintf(stderr, "sizes differ\n"), 1;
    const std::uint32_t w = plain_frame.width, h = plain_frame.height;
    const auto& plain = plain_frame.rgba;
    const auto& plain_ids = plain_frame.ids;
    const auto& outlined = outlined_frame.rgba;
    const auto& ids = outlined_frame.ids;
    const int width = std::atoi(argv[5]);
    const float crease = float(std::atof(argv[6]));
    const std::uint32_t colour = std::uint32_t(std::strtoul(argv[7], nullptr, 16));
    const std::vector<bool> mask = expected_outline(ids, int(w), int(h), width, crease);
    std::size_t outline = 0, hits = 0, wrong_outline = 0, wrong_rest = 0, other_hit = 0, outline_on_copies = 0;
    for (std::size_t i = 0; i < mask.size(); ++i) {
      if (!same_hit(plain_ids[i], ids[i])) ++other_hit;
      if (ids[i].atom != nano::gpu::kNoHit) ++hits;
      if (mask[i]) {
        ++outline;
        if (ids[i].atom != nano::gpu::kNoHit) ++outline_on_copies;
        if (outlined[i] != colour) ++wrong_outline;
      } else if (outlined[i] != plain[i]) {
        ++wrong_rest;
      }
    }
    std::printf("%ux%u: %zu hit pixels, %zu outline pixels (%zu of them on a molecule: creases and copies behind others); "
                "%zu outline pixels without the colour, %zu other pixels changed, %zu with another hit\n",
                w, h, hits, outline, outline_on_copies, wrong_outline, wrong_rest, other_hit);
    // Not vacuous: the view must have outlines on copies behind others and a tenth of its hit pixels
    // left plain (a view where every pixel is another copy would outline everything).
    if (outline_on_copies == 0 || 10 * (hits - outline_on_copies) < hits) return 1;
    return wrong_outline == 0 && wrong_rest == 0 && other_hit == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
