#pragma once
// What `nanobake bake` shows while it works: on a terminal one line per stage that updates in
// place (percent of the work announced so far, elapsed, remaining); elsewhere (a log, CI) one
// line per stage with its time; nothing with --quiet. The counts come from common/progress.hpp.
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

namespace nano::scene_bake {

// "nanobake: shells  47%  3.1 s, about 3.5 s left" ("about" once a second has passed and some
// work is done; before that, elapsed only).
std::string progress_line(const std::string& stage, std::uint64_t done, std::uint64_t total, double elapsed_seconds);

class ProgressDisplay {
public:
  enum class Mode { quiet, lines, terminal };
  // Terminal when `out` is one, lines otherwise.
  static Mode mode_for(std::FILE* out);

  ProgressDisplay(Mode mode, std::FILE* out);
  ~ProgressDisplay();
  ProgressDisplay(const ProgressDisplay&) = delete;
  ProgressDisplay& operator=(const ProgressDisplay&) = delete;

  void begin(const std::string& stage);
  void end(const std::string& stage, double seconds);

private:
  void redraw_loop();
  Mode mode_;
  std::FILE* out_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::string stage_;  // empty between stages
  std::chrono::steady_clock::time_point start_;
  bool stopping_ = false;
  std::thread redraw_;
};

}  // namespace nano::scene_bake
