#pragma once
// Progressive refinement (host side, no Vulkan): how far to reduce the resolution while the camera
// moves and at each refinement step once it rests, the nearest-neighbour upscale of a reduced frame, and the running average of successive
// full-resolution frames (different ambient-occlusion samples) while it rests.
#include <cstdint>
#include <span>
#include <vector>

namespace nano::viewer {

// The reduction factor (2, 4, 8 or 16 per axis) for frames rendered while the camera moves: the
// smallest that keeps the frame under `budget_seconds` at the measured cost per pixel; 2 while no
// cost is known yet.
std::uint32_t motion_scale(double seconds_per_pixel, std::uint32_t width, std::uint32_t height, double budget_seconds);
// The first frame of a session, before any cost is known, is rendered at 1/kFirstFrameScale per
// axis: it measures the cost and is on screen at once whatever the scene costs (open → first image).
constexpr std::uint32_t kFirstFrameScale = 8;

// The reduction factor of the next frame while the camera rests, after one at `shown_scale` of the
// same state (0: none shown yet): the finest of 1, 2, 4, 8, 16 whose frame fits `budget_seconds`,
// but at most half of `shown_scale`, so refinement always moves on (1/4 → 1/2 → full when each
// step costs more than the budget). kFirstFrameScale while no cost is known: that frame measures it.
std::uint32_t rest_scale(std::uint32_t shown_scale, double seconds_per_pixel, std::uint32_t width, std::uint32_t height,
                         double budget_seconds);
// ceil(size / scale), at least 1.
std::uint32_t reduced_extent(std::uint32_t size, std::uint32_t scale);

// `source` (sw × sh) stretched to dw × dh by nearest neighbour, pixel centres aligned.
std::vector<std::uint32_t> resample_nearest(std::span<const std::uint32_t> source, std::uint32_t sw, std::uint32_t sh,
                                            std::uint32_t dw, std::uint32_t dh);

// sRGB-encoded 8-bit ↔ linear [0, 1] (IEC 61966-2-1).
float srgb_to_linear(std::uint8_t value);
std::uint8_t linear_to_srgb(float value);

// Averages RGBA8 sRGB frames in linear light: averaging the encoded bytes would darken every
// partly occluded pixel.
class Accumulator {
public:
  // Forgets every sample; the next add() starts a new average of that size.
  void reset() { count_ = 0; }
  void add(std::span<const std::uint32_t> rgba, std::uint32_t width, std::uint32_t height);
  std::uint32_t count() const { return count_; }
  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  // The average, sRGB-encoded; exactly the one frame added when count() == 1 (alpha is averaged
  // as a plain number).
  const std::vector<std::uint32_t>& result() const { return result_; }

private:
  std::uint32_t count_ = 0, width_ = 0, height_ = 0;
  std::vector<float> sum_;  // linear RGBA per pixel
  std::vector<std::uint32_t> result_;
};

}  // namespace nano::viewer
