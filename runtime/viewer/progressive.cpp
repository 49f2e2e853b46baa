#include "runtime/viewer/progressive.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace nano::viewer {
namespace {

const std::array<float, 256>& srgb_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double c = i / 255.0;
      t[i] = float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
    }
    return t;
  }();
  return table;
}

}  // namespace

std::uint32_t motion_scale(double seconds_per_pixel, std::uint32_t width, std::uint32_t height, double budget_seconds) {
  if (!(seconds_per_pixel > 0)) return 2;
  std::uint32_t scale = 2;
  while (scale < 16) {
    const double pixels = double(reduced_extent(width, scale)) * reduced_extent(height, scale);
    if (pixels * seconds_per_pixel <= budget_seconds) break;
    scale *= 2;
  }
  return scale;
}

std::uint32_t rest_scale(std::uint32_t shown_scale, double seconds_per_pixel, std::uint32_t width, std::uint32_t height,
                         double budget_seconds) {
  if (!(seconds_per_pixel > 0)) return shown_scale == 0 ? kFirstFrameScale : std::max<std::uint32_t>(shown_scale / 2, 1);
  const std::uint32_t coarsest = shown_scale == 0 ? 16 : std::max<std::uint32_t>(shown_scale / 2, 1);
  for (std::uint32_t scale = 1; scale < coarsest; scale *= 2) {
    const double pixels = double(reduced_extent(width, scale)) * reduced_extent(height, scale);
    if (pixels * seconds_per_pixel <= budget_seconds) return scale;
  }
  return coarsest;
}

std::uint32_t reduced_extent(std::uint32_t size, std::uint32_t scale) {
  return std::max<std::uint32_t>(1, (size + scale - 1) / std::max<std::uint32_t>(scale, 1));
}

std::vector<std::uint32_t> resample_nearest(std::span<const std::uint32_t> source, std::uint32_t sw, std::uint32_t sh,
                                            std::uint32_t dw, std::uint32_t dh) {
  if (source.size() != std::size_t(sw) * sh) throw std::invalid_argument("resample_nearest: source size does not match");
  std::vector<std::uint32_t> out(std::size_t(dw) * dh);
  if (sw == 0 || sh == 0) return out;
  std::vector<std::uint32_t> column(dw);
  for (std::uint32_t x = 0; x < dw; ++x)
    column[x] = std::min<std::uint32_t>(sw - 1, std::uint32_t((std::uint64_t(2 * x + 1) * sw) / (2ull * dw)));
  for (std::uint32_t y = 0; y < dh; ++y) {
    const std::uint32_t sy = std::min<std::uint32_t>(sh - 1, std::uint32_t((std::uint64_t(2 * y + 1) * sh) / (2ull * dh)));
    const std::uint32_t* row = source.data() + std::size_t(sy) * sw;
    std::uint32_t* target = out.data() + std::size_t(y) * dw;
    for (std::uint32_t x = 0; x < dw; ++x) target[x] = row[column[x]];
  }
  return out;
}

float srgb_to_linear(std::uint8_t value) { return srgb_table()[value]; }

std::uint8_t linear_to_srgb(float value) {
  const double c = std::clamp(double(value), 0.0, 1.0);
  const double s = c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
  return std::uint8_t(std::lround(std::clamp(s, 0.0, 1.0) * 255));
}

void Accumulator::add(std::span<const std::uint32_t> rgba, std::uint32_t width, std::uint32_t height) {
  if (rgba.size() != std::size_t(width) * height) throw std::invalid_argument("Accumulator::add: size does not match");
  if (count_ == 0 || width != width_ || height != height_) {
    count_ = 0;
    width_ = width, height_ = height;
    sum_.assign(rgba.size() * 4, 0.0f);
  }
  ++count_;
  for (std::size_t i = 0; i < rgba.size(); ++i) {
    for (int c = 0; c < 3; ++c) sum_[4 * i + c] += srgb_to_linear(std::uint8_t(rgba[i] >> (8 * c)));
    sum_[4 * i + 3] += float(rgba[i] >> 24) / 255.0f;
  }
  if (count_ == 1) {
    result_.assign(rgba.begin(), rgba.end());
    return;
  }
  result_.resize(rgba.size());
  const float inverse = 1.0f / float(count_);
  for (std::size_t i = 0; i < rgba.size(); ++i) {
    std::uint32_t word = 0;
    for (int c = 0; c < 3; ++c) word |= std::uint32_t(linear_to_srgb(sum_[4 * i + c] * inverse)) << (8 * c);
    word |= std::uint32_t(std::lround(std::clamp(sum_[4 * i + 3] * inverse, 0.0f, 1.0f) * 255)) << 24;
    result_[i] = word;
  }
}

}  // namespace nano::viewer
