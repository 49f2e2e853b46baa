#pragma once
// One render as the effect checks read it back: its colours (PNG) and its ids image, of one size.
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/render/image_io.hpp"

namespace nano::render::test {

struct RenderedFrame {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint32_t> rgba;
  std::vector<gpu::PixelHit> ids;
  bool same_size(const RenderedFrame& o) const { return width == o.width && height == o.height; }
};

// The same atom of the same copy at the same depth (the background's infinite depths equal): what an
// effect that changes colour only must leave every pixel of a frame.
inline bool same_hit(const gpu::PixelHit& a, const gpu::PixelHit& b) {
  return a.atom == b.atom && a.copy_number_lo == b.copy_number_lo && a.copy_number_hi == b.copy_number_hi &&
         (a.depth == b.depth || (std::isinf(a.depth) && std::isinf(b.depth)));
}

inline RenderedFrame read_rendered_frame(const std::string& png, const std::string& ids) {
  RenderedFrame f;
  std::uint32_t iw = 0, ih = 0;
  f.rgba = read_png(png, f.width, f.height);
  f.ids = read_ids(ids, iw, ih);
  if (iw != f.width || ih != f.height) throw std::runtime_error(png + " and " + ids + " differ in size");
  return f;
}

}  // namespace nano::render::test
