#include "runtime/bench/frame_stats.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace nano::bench {

FrameStats frame_stats(std::vector<double> seconds) {
  if (seconds.empty()) throw std::invalid_argument("frame_stats: no frames measured");
  std::sort(seconds.begin(), seconds.end());
  const std::size_t n = seconds.size();
  const auto rank = [&](double p) { return seconds[std::min(n - 1, std::size_t(std::ceil(p * double(n))) - 1)]; };
  FrameStats s;
  s.frames = n;
  s.min = seconds.front();
  s.median = n % 2 ? seconds[n / 2] : 0.5 * (seconds[n / 2 - 1] + seconds[n / 2]);
  s.p95 = rank(0.95);
  s.mean = std::accumulate(seconds.begin(), seconds.end(), 0.0) / double(n);
  return s;
}

nlohmann::json to_json(const FrameStats& s) {
  return {{"min", s.min}, {"median", s.median}, {"p95", s.p95}, {"mean", s.mean}, {"frames", s.frames}};
}

}  // namespace nano::bench
