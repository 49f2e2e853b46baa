#include "common/progress.hpp"

#include <algorithm>
#include <atomic>

namespace nano::progress {
namespace {

std::atomic<std::uint64_t> done_steps{0}, announced_steps{0};

}  // namespace

void add_work(std::uint64_t units) { announced_steps.fetch_add(units, std::memory_order_relaxed); }
void advance(std::uint64_t units) { done_steps.fetch_add(units, std::memory_order_relaxed); }

std::pair<std::uint64_t, std::uint64_t> counts() {
  const std::uint64_t done = done_steps.load(std::memory_order_relaxed);
  return {done, std::max(done, announced_steps.load(std::memory_order_relaxed))};
}

void reset() {
  done_steps.store(0, std::memory_order_relaxed);
  announced_steps.store(0, std::memory_order_relaxed);
}

}  // namespace nano::progress
