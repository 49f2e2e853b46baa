#pragma once
// Summaries of the per-pixel work counters of shared/ray_counters.h (`nanoview bench --counters`):
// per counter the mean over pixels, the 95th percentile and the maximum, plus two totals across
// levels — ray queries started and candidates met — the figures explicit instancing is held to.
#include <array>
#include <cstdint>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "shared/ray_counters.h"

namespace nano::bench {

// Rows of a summary: the counters of ray_counters.h in their order, then the two totals.
constexpr std::uint32_t kQueriesStarted = gpu::NANO_RAY_COUNTER_COUNT;
constexpr std::uint32_t kCandidatesMet = gpu::NANO_RAY_COUNTER_COUNT + 1;
constexpr std::uint32_t kCounterRows = gpu::NANO_RAY_COUNTER_COUNT + 2;

const char* counter_name(std::uint32_t row);  // snake_case key; throws std::out_of_range past the rows

struct CounterStat {
  double mean = 0;
  std::uint64_t p95 = 0;  // nearest rank, as FrameStats
  std::uint64_t max = 0;
};

struct CounterSummary {
  std::uint64_t pixels = 0;
  std::array<CounterStat, kCounterRows> rows{};
};

// `words`: NANO_RAY_COUNTER_COUNT per pixel, as a frame's counters. Throws std::invalid_argument
// when empty or not a whole number of pixels.
CounterSummary summarize_counters(std::span<const std::uint32_t> words);

nlohmann::ordered_json to_json(const CounterSummary& summary);

// A Markdown table of mean and p95 per row, one column pair per named summary.
std::string counters_markdown(std::span<const std::pair<std::string, CounterSummary>> columns);

}  // namespace nano::bench
