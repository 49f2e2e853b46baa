#pragma once
// Summaries of measured frame times: a noisy shared machine makes the median and the 95th
// percentile the figures worth reporting, never a single frame.
#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

namespace nano::bench {

struct FrameStats {
  double min = 0, median = 0, p95 = 0, mean = 0;
  std::size_t frames = 0;
};

// Nearest-rank percentiles (p95 = the ⌈0.95·n⌉-th smallest). Throws std::invalid_argument when empty.
FrameStats frame_stats(std::vector<double> seconds);
nlohmann::json to_json(const FrameStats& stats);

}  // namespace nano::bench
