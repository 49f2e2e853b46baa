#pragma once
// One way to spread independent work over threads: a worker that throws (bad input, bad_alloc, a
// CGAL precondition) becomes an exception in the caller, never std::terminate.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

#include "common/progress.hpp"

namespace nano {

// Calls task(i) for every i in [0, count) on up to `threads` threads, the caller's among them,
// handing out indices one at a time (uneven tasks balance themselves). Once every task has run or
// thrown, the exception of the lowest index that threw is rethrown, so which error the caller sees
// does not depend on scheduling. Each task counts as one step of progress (common/progress.hpp).
template <class Task>
void parallel_for(std::size_t count, int threads, const Task& task) {
  std::vector<std::exception_ptr> errors(count);
  std::atomic<std::size_t> next{0};
  progress::add_work(count);
  const auto worker = [&] {
    for (std::size_t i = next++; i < count; i = next++) {
      try {
        task(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
      progress::advance();
    }
  };
  {
    std::vector<std::jthread> pool;
    const std::size_t workers = std::min<std::size_t>(count, static_cast<std::size_t>(std::max(threads, 1)));
    for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(worker);
    worker();
  }
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace nano
