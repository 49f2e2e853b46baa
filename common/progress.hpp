#pragma once
// How far the long-running work of this process has got: loops deep in the baker (every
// parallel_for, the tile packers) count their steps here, so that a command can show a stage's
// progress without each library knowing about terminals. Process-wide on purpose: the stages
// run one at a time and the counts are only ever shown, never used to decide anything.
#include <cstdint>
#include <utility>

namespace nano::progress {

// Announces `units` more steps of the current stage's work.
void add_work(std::uint64_t units);
// Marks `units` steps done.
void advance(std::uint64_t units = 1);
// (done, announced) since the last reset.
std::pair<std::uint64_t, std::uint64_t> counts();
// Starts counting a new stage from zero.
void reset();

}  // namespace nano::progress
