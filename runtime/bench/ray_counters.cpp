#include "runtime/bench/ray_counters.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace nano::bench {
namespace {

constexpr const char* kNames[kCounterRows] = {
    "ulas_queries",      "ulas_candidates", "prism_tests",       "prisms_entered", "replas_queries",   "slots_tried",
    "mlas_queries",      "mlas_candidates", "ownership_rejects", "listed_rejects", "nlas_queries",     "nlas_candidates",
    "sphere_tests",      "core_steps",      "core_boxes",        "mask_rejects",   "flat_queries",     "flat_candidates",
    "medium_steps",      "medium_keep_queries", "medium_rejects",
    "queries_started",   "candidates_met"};

std::uint64_t row_value(std::span<const std::uint32_t> pixel, std::uint32_t row) {
  using namespace gpu;
  if (row == kQueriesStarted)
    return std::uint64_t(pixel[NANO_RC_ULAS_QUERIES]) + pixel[NANO_RC_REPLAS_QUERIES] + pixel[NANO_RC_MLAS_QUERIES] +
           pixel[NANO_RC_NLAS_QUERIES] + pixel[NANO_RC_FLAT_QUERIES] + pixel[NANO_RC_MEDIUM_KEEP_QUERIES];
  if (row == kCandidatesMet)
    return std::uint64_t(pixel[NANO_RC_ULAS_CANDIDATES]) + pixel[NANO_RC_SLOTS_TRIED] + pixel[NANO_RC_MLAS_CANDIDATES] +
           pixel[NANO_RC_NLAS_CANDIDATES] + pixel[NANO_RC_FLAT_CANDIDATES];
  return pixel[row];
}

}  // namespace

const char* counter_name(std::uint32_t row) {
  if (row >= kCounterRows) throw std::out_of_range("counter_name: no row " + std::to_string(row));
  return kNames[row];
}

CounterSummary summarize_counters(std::span<const std::uint32_t> words) {
  constexpr std::size_t n = gpu::NANO_RAY_COUNTER_COUNT;
  if (words.empty() || words.size() % n != 0)
    throw std::invalid_argument("summarize_counters: " + std::to_string(words.size()) + " words is not a whole number of " +
                                std::to_string(n) + "-word pixels");
  CounterSummary s;
  s.pixels = words.size() / n;
  std::vector<std::uint64_t> values(s.pixels);
  for (std::uint32_t row = 0; row < kCounterRows; ++row) {
    double sum = 0;
    for (std::size_t p = 0; p < s.pixels; ++p) {
      values[p] = row_value(words.subspan(p * n, n), row);
      sum += double(values[p]);
    }
    const std::size_t rank = (95 * s.pixels + 99) / 100;  // ⌈0.95·n⌉, 1-based
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(rank - 1), values.end());
    CounterStat& stat = s.rows[row];
    stat.p95 = values[rank - 1];
    stat.max = *std::max_element(values.begin(), values.end());
    stat.mean = sum / double(s.pixels);
  }
  return s;
}

nlohmann::ordered_json to_json(const CounterSummary& summary) {
  nlohmann::ordered_json out;
  out["pixels"] = summary.pixels;
  for (std::uint32_t row = 0; row < kCounterRows; ++row)
    out["per_pixel"][counter_name(row)] = {{"mean", summary.rows[row].mean}, {"p95", summary.rows[row].p95},
                                           {"max", summary.rows[row].max}};
  return out;
}

std::string counters_markdown(std::span<const std::pair<std::string, CounterSummary>> columns) {
  std::string md = "| per pixel |";
  std::string rule = "|---|";
  for (const auto& [name, summary] : columns) md += " " + name + " mean | p95 |", rule += "---|---|";
  md += "\n" + rule + "\n";
  for (std::uint32_t row = 0; row < kCounterRows; ++row) {
    md += std::string("| ") + counter_name(row) + " |";
    for (const auto& [name, summary] : columns) {
      char cell[64];
      std::snprintf(cell, sizeof cell, " %.2f | %llu |", summary.rows[row].mean, (unsigned long long)summary.rows[row].p95);
      md += cell;
    }
    md += "\n";
  }
  return md;
}

}  // namespace nano::bench
