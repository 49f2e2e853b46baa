// The bench report helpers: nearest-rank statistics against hand-computed values, what a frame
// shows counted by hand, and the SVG plot's structure (every drawable point placed inside the frame, log axes refusing what they cannot show).
#include <cstdint>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "runtime/bench/frame_stats.hpp"
#include "runtime/bench/on_screen.hpp"
#include "runtime/bench/ray_counters.hpp"
#include "runtime/bench/svg_plot.hpp"

namespace {

using namespace nano::bench;

// Two types (atoms [0, 10) and [10, 15)); five pixels: two of one copy of the first, one of a copy
// of the second, one background, one of another copy of the first.
TEST(OnScreen, CopiesAtomsAndPixelsCountedByHand) {
  std::vector<nano::gpu::MoleculeType> types(2);
  types[0].first_atom = 0, types[0].atom_count = 10;
  types[1].first_atom = 10, types[1].atom_count = 5;
  const auto hit = [](std::uint32_t atom, std::uint64_t copy) {
    nano::gpu::PixelHit h{};
    h.atom = atom;
    h.copy_number_lo = std::uint32_t(copy), h.copy_number_hi = std::uint32_t(copy >> 32);
    return h;
  };
  const std::vector<nano::gpu::PixelHit> hits{hit(3, 7), hit(4, 7), hit(12, 1ull << 33), hit(nano::gpu::kNoHit, 0), hit(9, 8)};
  const OnScreen seen = on_screen(types, hits);
  EXPECT_EQ(seen.hit_pixels, 4u);
  EXPECT_EQ(seen.copies, 3u);
  EXPECT_EQ(seen.atoms, 10u + 5u + 10u);
  EXPECT_EQ(on_screen(types, {}).hit_pixels, 0u);
}

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

// 20 pixels: pixel p has p + 1 µLAS candidates, one query at each level except the repLAS, and
// 2p slots; the totals add the levels.
TEST(RayCounters, MeansPercentilesAndTotalsByHand) {
  using namespace nano::gpu;
  std::vector<std::uint32_t> words(20 * NANO_RAY_COUNTER_COUNT, 0);
  for (std::uint32_t p = 0; p < 20; ++p) {
    std::uint32_t* w = &words[p * NANO_RAY_COUNTER_COUNT];
    w[NANO_RC_ULAS_QUERIES] = 1, w[NANO_RC_MLAS_QUERIES] = 1, w[NANO_RC_NLAS_QUERIES] = 1;
    w[NANO_RC_ULAS_CANDIDATES] = p + 1;
    w[NANO_RC_SLOTS_TRIED] = 2 * p;
  }
  const CounterSummary s = summarize_counters(words);
  EXPECT_EQ(s.pixels, 20u);
  EXPECT_DOUBLE_EQ(s.rows[NANO_RC_ULAS_CANDIDATES].mean, 10.5);
  EXPECT_EQ(s.rows[NANO_RC_ULAS_CANDIDATES].p95, 19u);  // the 19th smallest of 1 … 20
  EXPECT_EQ(s.rows[NANO_RC_ULAS_CANDIDATES].max, 20u);
  EXPECT_DOUBLE_EQ(s.rows[kQueriesStarted].mean, 3.0);
  EXPECT_EQ(s.rows[kQueriesStarted].p95, 3u);
  EXPECT_DOUBLE_EQ(s.rows[kCandidatesMet].mean, 10.5 + 19.0);  // (p + 1) + 2p summed over p, over 20
  EXPECT_EQ(s.rows[kCandidatesMet].max, 20u + 38u);
  EXPECT_DOUBLE_EQ(s.rows[NANO_RC_SPHERE_TESTS].mean, 0.0);
  EXPECT_STREQ(counter_name(NANO_RC_SPHERE_TESTS), "sphere_tests");
  EXPECT_STREQ(counter_name(kCandidatesMet), "candidates_met");
  EXPECT_THROW(counter_name(kCounterRows), std::out_of_range);
  const nlohmann::ordered_json j = to_json(s);
  EXPECT_EQ(j["per_pixel"]["slots_tried"]["max"], 38);
  const std::pair<std::string, CounterSummary> columns[] = {{"a", s}};
  EXPECT_NE(counters_markdown(columns).find("| ulas_candidates | 10.50 | 19 |"), std::string::npos);
}

TEST(RayCounters, RefusesPartialPixels) {
  EXPECT_THROW(summarize_counters(std::vector<std::uint32_t>{}), std::invalid_argument);
  EXPECT_THROW(summarize_counters(std::vector<std::uint32_t>(nano::gpu::NANO_RAY_COUNTER_COUNT + 1)), std::invalid_argument);
}

TEST(SvgPlot, PointsInsideTheFrameAndLabelled) {
  PlotSpec spec;
  spec.title = "cost <of> & accuracy";
  spec.x_label = "time";
  spec.y_label = "error";
  spec.series.push_back({"shell", {{1.0, 0.0, "default"}, {0.8, 12.5, "fixed"}}, false});
  spec.series.push_back({"levels", {{3.9, 0.1, "2"}}, true});
  const std::string svg = svg_plot(spec, "plot.json");
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
  const std::string svg = svg_plot(spec, "plot.json");
  EXPECT_NE(svg.find("1 point(s) not drawable"), std::string::npos);
  spec.series = {{"none", {{0, 0}}, false}};
  try {
    (void)svg_plot(spec, "plot.json");
    ADD_FAILURE() << "drew a plot without a drawable point";
  } catch (const nano::InputError& e) {
    EXPECT_EQ(e.file(), "plot.json") << e.what();
  }
}

}  // namespace
