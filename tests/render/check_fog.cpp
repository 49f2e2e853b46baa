// Fog changes colour only, and exactly as docs/effects.md says: with the same camera the fogged frame
// hits the very same atoms; the background keeps its colour; every hit pixel at depth t shows the
// plain frame's colour mixed (in linear light) towards the white background by
//   STRENGTH · smoothstep(near + START·e, near + (START + SPAN)·e, z),  e = max(far − near, near / 10)
// z = t·cos θ its view depth (θ between its ray and the view axis, from the pixel's place in a pinhole
// image of vertical field FOV), near and far the least and greatest z hit among the pixels
// (⌊(2i + 1)·W / 16⌋, ⌊(2j + 1)·H / 16⌋), i, j = 0..7 (±2 per channel: the plain colour was already
// rounded to 8 bits); and the check is not vacuous: a share of the hit pixels must be fogged by at
// least a tenth.
// Usage: check_fog PLAIN.png PLAIN.ids FOG.png FOG.ids START SPAN STRENGTH MIN_FOGGED_SHARE FOV_DEGREES
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "tests/render/rendered_frame.hpp"

namespace {

double linear_from_srgb(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double srgb_from_linear(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}
int channel(std::uint32_t rgba, int c) { return int((rgba >> (8 * c)) & 255u); }

}  // namespace

int main(int argc, char** argv) {
  if (argc != 10)
    return std::fprintf(stderr, "usage: check_fog PLAIN.png PLAIN.ids FOG.png FOG.ids START SPAN STRENGTH MIN_SHARE FOV_DEGREES\n"), 2;
  try {
    using nano::render::test::read_rendered_frame;
    const auto plain = read_rendered_frame(argv[1], argv[2]);
    const auto fogged = read_rendered_frame(argv[3], argv[4]);
    if (!plain.same_size(fogged)) return std::fprintf(stderr, "sizes differ\n"), 1;
    const double half_height = std::tan(std::atof(argv[9]) * M_PI / 360), aspect = double(plain.width) / plain.height;
    const auto view_depth = [&](std::size_t x, std::size_t y, double t) {
      const double u = (2 * (x + 0.5) / plain.width - 1) * half_height * aspect, v = (1 - 2 * (y + 0.5) / plain.height) * half_height;
      return t / std::sqrt(1 + u * u + v * v);
    };
    double near = INFINITY, far = -INFINITY;
    for (std::uint32_t j = 0; j < 8; ++j)
      for (std::uint32_t i = 0; i < 8; ++i) {
        const std::size_t x = (2 * i + 1) * plain.width / 16, y = (2 * j + 1) * plain.height / 16;
        const auto& h = plain.ids[y * plain.width + x];
        if (h.atom != nano::gpu::kNoHit)
          near = std::min(near, view_depth(x, y, h.depth)), far = std::max(far, view_depth(x, y, h.depth));
      }
    if (!(near <= far)) return std::fprintf(stderr, "no pixel of the 8 x 8 grid hit anything: the view proves nothing\n"), 1;
    const double extent = std::max(far - near, near / 10);
    const double start = near + std::atof(argv[5]) * extent, span = std::atof(argv[6]) * extent;
    const double strength = std::atof(argv[7]);
    std::size_t hits = 0, fogged_tenth = 0, wrong = 0, other_hit = 0, background_changed = 0;
    for (std::size_t i = 0; i < plain.rgba.size(); ++i) {
      const auto& a = plain.ids[i];
      if (!nano::render::test::same_hit(a, fogged.ids[i])) {
        ++other_hit;
        continue;
      }
      if (a.atom == nano::gpu::kNoHit) {
        background_changed += plain.rgba[i] != fogged.rgba[i];
        continue;
      }
      ++hits;
      const double z = view_depth(i % plain.width, i / plain.width, a.depth);
      const double u = span > 0 ? std::clamp((z - start) / span, 0.0, 1.0) : (z > start ? 1.0 : 0.0);
      const double f = strength * u * u * (3 - 2 * u);
      fogged_tenth += f >= 0.1;
      for (int c = 0; c < 3; ++c) {
        const double lin = linear_from_srgb(channel(plain.rgba[i], c) / 255.0);
        const double expected = 255 * srgb_from_linear(lin + f * (1 - lin));
        if (std::abs(expected - channel(fogged.rgba[i], c)) > 2.5) {
          if (wrong < 5)
            std::printf("pixel (%zu, %zu) channel %d at depth %.1f: expected %.1f (fog %.3f over %d), got %d\n", i % plain.width,
                        i / plain.width, c, double(a.depth), expected, f, channel(plain.rgba[i], c), channel(fogged.rgba[i], c));
          ++wrong;
          break;
        }
      }
    }
    const double share = hits ? double(fogged_tenth) / double(hits) : 0.0;
    std::printf("%zu hit pixels, %zu fogged by a tenth or more (%.3f); %zu not as the rule says, %zu background pixels changed, "
                "%zu with another hit\n",
                hits, fogged_tenth, share, wrong, background_changed, other_hit);
    std::printf("depth range of the grid: %.1f to %.1f Å\n", near, far);
    return wrong == 0 && other_hit == 0 && background_changed == 0 && hits > 0 && share >= std::atof(argv[8]) ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
