// Outlines are exactly what the rule of docs/effects.md makes of the ids image. With the same camera,
// a frame with outlines must show, on every pixel, the plain frame's colour mixed towards the outline
// colour by the strength the rule computes from the ids and depths around it (±1 per channel for
// rounding); the hits must not change.
// The rule, written here from docs/effects.md and not from the shader: for each pixel q within WIDTH
// (Chebyshev distance, inside the image) that was hit and is nearer than the pixel p (the background
// is infinitely far), with f = depth(q)·2·tan(fov/2)/height the Å one pixel spans at q:
//   shown = ramp(FADE/2, FADE, R/f), R the bounding radius of q's molecule type (1 when FADE is 0);
//   same copy:    shown · ramp(c, 2c, depth(p) − depth(q)), c = max(CREASE, 2f);
//   another copy: max(shown, step), step = 1 when p is background, else
//                 ramp(8, 32, (depth(p) − depth(q)) / f) · ramp(1, 3, R/f);
// p's strength is the largest over its q, ramp the smoothstep from 0 to 1.
// It also reports, for the measures: the share of hit pixels outlines change, and for a named
// molecule type, every copy of it that covers MIN_PIXELS must have ≥ 90 % of the pixels around it (just
// outside, farther) darkened at least half-way.
// Usage: check_outlines PKG PLAIN.png PLAIN.ids OUTLINED.png OUTLINED.ids WIDTH CREASE FADE RGBA_HEX FOV_DEGREES
//        [MAX_CHANGED_SHARE [TYPE MIN_PIXELS]]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "format/package_view.hpp"
#include "format/validator.hpp"
#include "tests/render/rendered_frame.hpp"

namespace {

using nano::gpu::PixelHit;
constexpr std::uint32_t kNoHit = nano::gpu::kNoHit;

struct Rule {
  int width;
  double crease, fade, pixel_per_depth;  // pixel_per_depth: Å a pixel spans per Å of depth
  std::vector<double> reach;             // per molecule type
  const nano::format::PackageView* view;

  std::uint32_t type_of(std::uint32_t atom) const {
    for (std::uint32_t t = 0; t < view->molecules.size(); ++t)
      if (atom >= view->molecules[t].first_atom && atom - view->molecules[t].first_atom < view->molecules[t].atom_count) return t;
    return ~0u;
  }
};

double ramp(double lo, double hi, double x) {
  const double u = std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
  return u * u * (3 - 2 * u);
}

double depth_of(const PixelHit& p) { return p.atom == kNoHit ? std::numeric_limits<double>::infinity() : double(p.depth); }

bool same_copy(const PixelHit& a, const PixelHit& b) {
  return a.atom != kNoHit && a.copy_number_lo == b.copy_number_lo && a.copy_number_hi == b.copy_number_hi;
}

std::vector<double> expected_strength(const std::vector<PixelHit>& ids, int w, int h, const Rule& rule) {
  std::vector<double> out(ids.size(), 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const PixelHit& here = ids[std::size_t(y) * w + x];
      double strength = 0;
      for (int qy = std::max(0, y - rule.width); qy <= std::min(h - 1, y + rule.width); ++qy)
        for (int qx = std::max(0, x - rule.width); qx <= std::min(w - 1, x + rule.width); ++qx) {
          const PixelHit& there = ids[std::size_t(qy) * w + qx];
          if (there.atom == kNoHit || !(depth_of(there) < depth_of(here))) continue;
          const double pixel = std::max(depth_of(there) * rule.pixel_per_depth, 1e-30);
          const std::uint32_t type = rule.type_of(there.atom);
          const double reach = type < rule.reach.size() ? rule.reach[type] : 0.0;
          const double shown = rule.fade > 0 ? ramp(rule.fade / 2, rule.fade, reach / pixel) : 1.0;
          const double gap = depth_of(here) - depth_of(there);
          const double fold = std::max(rule.crease, 2 * pixel);
          const double step = here.atom == kNoHit ? 1.0 : ramp(8, 32, gap / pixel) * ramp(1, 3, reach / pixel);
          const double edge = same_copy(here, there) ? shown * ramp(fold, 2 * fold, gap) : std::max(shown, step);
          strength = std::max(strength, edge);
        }
      out[std::size_t(y) * w + x] = strength;
    }
  return out;
}

int channel(std::uint32_t rgba, int c) { return int((rgba >> (8 * c)) & 255u); }

std::uint32_t mixed(std::uint32_t a, std::uint32_t b, double s) {
  std::uint32_t out = 255u << 24;
  for (int c = 0; c < 3; ++c) out |= std::uint32_t(std::lround(channel(a, c) + s * (channel(b, c) - channel(a, c)))) << (8 * c);
  return out;
}

bool close(std::uint32_t a, std::uint32_t b) {
  for (int c = 0; c < 4; ++c)
    if (std::abs(channel(a, c) - channel(b, c)) > 1) return false;
  return true;
}

// Copies of `type` covering at least `min_pixels`, and how many of them have ≥ 90 % of their outer
// ring (8-neighbours of their pixels that show something farther) darkened half-way or more.
std::pair<std::size_t, std::size_t> outlined_copies(const std::vector<PixelHit>& ids, const std::vector<double>& strength, int w, int h,
                                                    const Rule& rule, std::uint32_t type, std::size_t min_pixels) {
  struct Count {
    std::size_t pixels = 0, ring = 0, dark = 0;
  };
  std::map<std::uint64_t, Count> copies;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const PixelHit& p = ids[std::size_t(y) * w + x];
      if (p.atom == kNoHit || rule.type_of(p.atom) != type) continue;
      const std::uint64_t key = (std::uint64_t(p.copy_number_hi) << 32) | p.copy_number_lo;
      ++copies[key].pixels;
    }
  for (auto& [key, count] : copies) {
    std::vector<bool> ring(ids.size(), false);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const PixelHit& p = ids[std::size_t(y) * w + x];
        if (p.atom == kNoHit || ((std::uint64_t(p.copy_number_hi) << 32) | p.copy_number_lo) != key) continue;
        for (int qy = std::max(0, y - 1); qy <= std::min(h - 1, y + 1); ++qy)
          for (int qx = std::max(0, x - 1); qx <= std::min(w - 1, x + 1); ++qx) {
            const std::size_t q = std::size_t(qy) * w + qx;
            if (!ring[q] && !same_copy(ids[q], p) && depth_of(ids[q]) > depth_of(p)) ring[q] = true;
          }
      }
    for (std::size_t q = 0; q < ring.size(); ++q)
      if (ring[q]) {
        ++count.ring;
        count.dark += strength[q] >= 0.5;
      }
  }
  std::size_t large = 0, outlined = 0;
  for (const auto& [key, count] : copies) {
    if (count.pixels < min_pixels) continue;
    ++large;
    outlined += count.ring > 0 && 10 * count.dark >= 9 * count.ring;
  }
  return {large, outlined};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 11 && argc != 12 && argc != 14)
    return std::fprintf(stderr, "usage: check_outlines PKG PLAIN.png PLAIN.ids OUTLINED.png OUTLINED.ids WIDTH CREASE FADE RGBA_HEX "
                                "FOV_DEGREES [MAX_CHANGED_SHARE [TYPE MIN_PIXELS]]\n"),
           2;
  try {
    const nano::format::Package package = nano::format::open_validated(argv[1]);
    const nano::format::PackageView view(package);
    using nano::render::test::read_rendered_frame;
    const auto plain_frame = read_rendered_frame(argv[2], argv[3]);
    const auto outlined_frame = read_rendered_frame(argv[4], argv[5]);
    if (!plain_frame.same_size(outlined_frame)) return std::fprintf(stderr, "sizes differ\n"), 1;
    const std::uint32_t w = plain_frame.width, h = plain_frame.height;
    const auto& plain = plain_frame.rgba;
    const auto& outlined = outlined_frame.rgba;
    const auto& ids = outlined_frame.ids;
    Rule rule{std::atoi(argv[6]), std::atof(argv[7]), std::atof(argv[8]), 0, {}, &view};
    const std::uint32_t colour = std::uint32_t(std::strtoul(argv[9], nullptr, 16));
    const double fov = std::atof(argv[10]) * M_PI / 180;
    rule.pixel_per_depth = 2 * std::tan(fov / 2) / h;
    for (const auto& m : view.molecules) rule.reach.push_back(m.aabb_min.w);
    const std::vector<double> strength = expected_strength(ids, int(w), int(h), rule);
    std::size_t hits = 0, changed_hits = 0, outline = 0, full = 0, wrong = 0, other_hit = 0;
    for (std::size_t i = 0; i < strength.size(); ++i) {
      const PixelHit& b = ids[i];
      if (!nano::render::test::same_hit(plain_frame.ids[i], b)) ++other_hit;
      const bool hit = b.atom != kNoHit;
      hits += hit;
      changed_hits += hit && outlined[i] != plain[i];
      outline += strength[i] > 0;
      full += strength[i] >= 1;
      if (!close(outlined[i], mixed(plain[i], colour, strength[i]))) {
        if (wrong < 5)
          std::printf("pixel (%zu, %zu): expected %08x (strength %.4f over %08x), got %08x\n", i % w, i / w,
                      mixed(plain[i], colour, strength[i]), strength[i], plain[i], outlined[i]);
        ++wrong;
      }
    }
    const double share = hits ? double(changed_hits) / double(hits) : 0.0;
    std::printf("%ux%u: %zu hit pixels, %zu changed by outlines (%.3f); %zu pixels with strength > 0, %zu at full strength; "
                "%zu pixels not as the rule says, %zu with another hit\n",
                w, h, hits, changed_hits, share, outline, full, wrong, other_hit);
    bool ok = wrong == 0 && other_hit == 0 && full > 0;  // not vacuous: some contour at full strength
    if (argc >= 12 && !(share <= std::atof(argv[11]))) {
      std::printf("outlines change %.3f of the hit pixels, more than %s\n", share, argv[11]);
      ok = false;
    }
    if (argc == 14) {
      std::uint32_t type = ~0u;
      for (std::uint32_t t = 0; t < view.molecules.size(); ++t)
        if (std::string(view.strings.data() + view.molecules[t].name_offset, view.molecules[t].name_length) == argv[12]) type = t;
      if (type == ~0u) return std::fprintf(stderr, "the package has no molecule type %s\n", argv[12]), 1;
      const auto [large, outlined_count] = outlined_copies(ids, strength, int(w), int(h), rule, type, std::size_t(std::atoi(argv[13])));
      std::printf("%s: %zu copies of at least %s pixels, %zu of them outlined\n", argv[12], large, argv[13], outlined_count);
      if (large == 0 || outlined_count != large) ok = false;
    }
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
