// Progressive refinement on the host: reduced sizes, nearest upscale, linear-light averaging.
#include <gtest/gtest.h>

#include "runtime/viewer/progressive.hpp"

namespace nano::viewer {
namespace {

TEST(Progressive, MotionScaleMeetsTheBudget) {
  EXPECT_EQ(motion_scale(0, 640, 480, 0.1), 2u);  // nothing measured yet
  EXPECT_EQ(motion_scale(1e-9, 640, 480, 0.1), 2u);
  const double per_pixel = 1e-5;  // 640x480 takes 3 s
  const std::uint32_t s = motion_scale(per_pixel, 640, 480, 0.1);
  EXPECT_LE(double(reduced_extent(640, s)) * reduced_extent(480, s) * per_pixel, 0.1);
  EXPECT_GT(double(reduced_extent(640, s / 2)) * reduced_extent(480, s / 2) * per_pixel, 0.1);
  EXPECT_EQ(motion_scale(1.0, 640, 480, 0.1), 16u);  // the coarsest it goes
  EXPECT_EQ(reduced_extent(5, 2), 3u);
  EXPECT_EQ(reduced_extent(1, 16), 1u);
}

TEST(Progressive, RestScaleStepsTowardsFullResolution) {
  EXPECT_EQ(rest_scale(0, 0, 1920, 1080, 0.3), kFirstFrameScale);  // nothing measured yet: a coarse first frame measures
  EXPECT_EQ(rest_scale(8, 0, 1920, 1080, 0.3), 4u);                // still unmeasured: refinement moves on
  const double cheap = 0.1 / (1920.0 * 1080);       // a full frame in 0.1 s: no steps
  EXPECT_EQ(rest_scale(0, cheap, 1920, 1080, 0.3), 1u);
  EXPECT_EQ(rest_scale(8, cheap, 1920, 1080, 0.3), 1u);
  const double slow = 4.0 / (1920.0 * 1080);  // full 4 s, 1/2 1 s, 1/4 0.25 s, 1/8 0.06 s
  EXPECT_EQ(rest_scale(0, slow, 1920, 1080, 0.3), 4u);   // a new state: the finest step within budget
  EXPECT_EQ(rest_scale(16, slow, 1920, 1080, 0.3), 4u);  // after motion: jumps the cheap steps
  EXPECT_EQ(rest_scale(4, slow, 1920, 1080, 0.3), 2u);   // then halves, each step shown
  EXPECT_EQ(rest_scale(2, slow, 1920, 1080, 0.3), 1u);
  const double very_slow = 1000.0 / (1920.0 * 1080);
  EXPECT_EQ(rest_scale(0, very_slow, 1920, 1080, 0.3), 16u);  // the coarsest it goes
  EXPECT_EQ(rest_scale(1, very_slow, 1920, 1080, 0.3), 1u);   // never coarser than full after full
}

TEST(Progressive, NearestUpscaleRepeatsPixels) {
  const std::vector<std::uint32_t> src{1, 2, 3, 4};  // 2x2
  const auto up = resample_nearest(src, 2, 2, 4, 4);
  const std::vector<std::uint32_t> expected{1, 1, 2, 2, 1, 1, 2, 2, 3, 3, 4, 4, 3, 3, 4, 4};
  EXPECT_EQ(up, expected);
  EXPECT_EQ(resample_nearest(src, 2, 2, 2, 2), src);
  EXPECT_EQ(resample_nearest(src, 2, 2, 1, 1).size(), 1u);
  EXPECT_THROW(resample_nearest(src, 3, 2, 1, 1), std::invalid_argument);
}

TEST(Progressive, SrgbRoundTripIsExact) {
  for (int v = 0; v < 256; ++v) EXPECT_EQ(linear_to_srgb(srgb_to_linear(std::uint8_t(v))), v);
}

TEST(Progressive, OneSampleIsTheFrameItself) {
  Accumulator a;
  const std::vector<std::uint32_t> frame{0xFF102030u, 0x80FFFFFFu};
  a.add(frame, 2, 1);
  EXPECT_EQ(a.count(), 1u);
  EXPECT_EQ(a.result(), frame);
}

TEST(Progressive, AveragesInLinearLight) {
  Accumulator a;
  const std::vector<std::uint32_t> black{0xFF000000u}, white{0xFFFFFFFFu};
  a.add(black, 1, 1);
  a.add(white, 1, 1);
  EXPECT_EQ(a.count(), 2u);
  // Half of white in linear light is sRGB 188, not the 128 of averaged bytes.
  const std::uint32_t mid = a.result()[0];
  EXPECT_EQ(mid & 0xFF, 188u);
  EXPECT_EQ((mid >> 8) & 0xFF, 188u);
  EXPECT_EQ(mid >> 24, 0xFFu);
  a.reset();
  a.add(white, 1, 1);
  EXPECT_EQ(a.result(), white);
}

TEST(Progressive, ANewSizeStartsANewAverage) {
  Accumulator a;
  a.add(std::vector<std::uint32_t>{0xFF000000u}, 1, 1);
  a.add(std::vector<std::uint32_t>(4, 0xFFFFFFFFu), 2, 2);
  EXPECT_EQ(a.count(), 1u);
  EXPECT_EQ(a.width(), 2u);
}

}  // namespace
}  // namespace nano::viewer
