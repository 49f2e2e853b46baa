#pragma once
// Shared by every micro-benchmark: where the in-repository structures live, and how a benchmark
// says its input is absent.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

namespace nano::bench {

// data/structures of the source tree (set by benchmarks/CMakeLists.txt), so CI needs no other clone.
inline std::filesystem::path structure_path(const std::string& file) {
  return std::filesystem::path(NANO_STRUCTURES_DIR) / file;
}

// The convention the smoke test (check_benchmark_json.py) accepts: an error whose message starts
// with "skipped:" is an input that is legitimately absent on this machine, any other is a failure.
// (Google Benchmark 1.7 has SkipWithError only; SkipWithMessage came with 1.8.)
inline void skip(benchmark::State& state, const std::string& why) {
  state.SkipWithError(("skipped: " + why).c_str());
}

}  // namespace nano::bench
