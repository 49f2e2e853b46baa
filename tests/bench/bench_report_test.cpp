// The bench report helpers: nearest-rank statistics against hand-computed values, and the SVG
// plot's structure (every drawable point placed inside the frame, log axes refusing what they cannot show).
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "runtime/bench/frame_stats.hpp"
#include "runtime/bench/svg_plot.hpp"

namespace {

using namespace nano::bench;

TEST(FrameStats, NearestRankPercentiles) {
  std::vector<double> s;
  for (int k = 20; k >= 1; --k) s.push_back(k * 0.1);  // 0.1 … 2.0, reversed
  const FrameStats f = frame_stats(s);
  EXPECT_EQ(f.frames, 20u);
  EXPECT_DOUBLE_EQ(f.min, 0.1);
  EXPECT_NEAR(f.median, 1.05, 1e-12);  // even count: mean of the 10th and 11th
  EXPECT_NEAR(f.p95, 1.9, 1e-12);      // ⌈0.95·20⌉ = 19th smallest
  EXPECT_NEAR(f.mean, 1.05, 1e-12);
  const FrameStats one = frame_stats({0.25});
  EXPECT_EQ(one.median, 0.25);
  EXPECT_EQ(one.p95, 0.25);
  EXPECT_THROW(frame_stats({}), std::invalid_argument);
  EXPECT_EQ(to_json(f)["p95"].get<double>(), f.p95);
}

TEST(SvgPlot, PointsInsideTheFrameAndLabelled) {
  PlotSpec spec;
  spec.title = "cost <of> & accuracy";
  spec.x_label = "time";
  spec.y_label = "error";
  spec.series.push_back({"shell", {{1.0, 0.0, "default"}, {0.8, 12.5, "fixed"}}, false});
  spec.series.push_back({"levels", {{3.9, 0.1, "2"}}, true});
  const std::string svg = svg_plot(spec);
  EXPECT_NE(svg.find("cost &lt;of&gt; &amp; accuracy"), std::string::npos);  // escaped
  const std::regex circle("<circle cx=\"([0-9.e+-]+)\" cy=\"([0-9.e+-]+)\" r=\"4\"");
  int points = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), circle); it != std::sregex_iterator(); ++it) {
    const double x = std::stod((*it)[1]), y = std::stod((*it)[2]);
    EXPECT_GE(x, 80.0);
    EXPECT_LE(x, 800.0);
    EXPECT_GE(y, 0.0);
    EXPECT_LE(y, 500.0);
    ++points;
  }
  EXPECT_EQ(points, 3 + 2);  // three points and two legend marks
  EXPECT_NE(svg.find(">fixed<"), std::string::npos);
}

TEST(SvgPlot, LogAxesLeaveOutWhatTheyCannotShow) {
  PlotSpec spec;
  spec.log_x = spec.log_y = true;
  spec.series.push_back({"scale", {{1, 0.5}, {1000, 2.0}, {10, 0.0}}, true});
  const std::string svg = svg_plot(spec);
  EXPECT_NE(svg.find("1 point(s) not drawable"), std::string::npos);
  spec.series = {{"none", {{0, 0}}, false}};
  EXPECT_THROW(svg_plot(spec), std::invalid_argument);
}

}  // namespace
