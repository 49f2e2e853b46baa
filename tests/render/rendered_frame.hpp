#pragma once
// One render as the effect checks read it back: its colours (PNG) and its ids image, of one size.
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

inline RenderedFrame read_rendered_frame(const std::string& png, const std::string& ids) {
  RenderedFrame f;
  std::uint32_t iw = 0, ih = 0;
  f.rgba = read_png(png, f.width, f.height);
  f.ids = read_ids(ids, iw, ih);
  if (iw != f.width || ih != f.height) throw std::runtime_error(png + " and " + ids + " differ in size");
  return f;
}

}  // namespace nano::render::test
