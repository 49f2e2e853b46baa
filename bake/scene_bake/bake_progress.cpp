#include "bake/scene_bake/bake_progress.hpp"

#include <unistd.h>

#include "common/progress.hpp"

namespace nano::scene_bake {
namespace {

constexpr auto kRedrawEvery = std::chrono::milliseconds(200);

}  // namespace

std::string progress_line(const std::string& stage, std::uint64_t done, std::uint64_t total, double elapsed_seconds) {
  char text[256];
  if (total == 0 || done == 0) {
    std::snprintf(text, sizeof text, "nanobake: %s  %.1f s", stage.c_str(), elapsed_seconds);
    return text;
  }
  const double fraction = static_cast<double>(done) / static_cast<double>(total);
  if (elapsed_seconds < 1.0 || done >= total) {
    std::snprintf(text, sizeof text, "nanobake: %s  %3.0f%%  %.1f s", stage.c_str(), 100.0 * fraction, elapsed_seconds);
    return text;
  }
  const double left = elapsed_seconds * (1.0 - fraction) / fraction;
  std::snprintf(text, sizeof text, "nanobake: %s  %3.0f%%  %.1f s, about %.0f s left", stage.c_str(), 100.0 * fraction,
                elapsed_seconds, left);
  return text;
}

ProgressDisplay::Mode ProgressDisplay::mode_for(std::FILE* out) {
  return isatty(fileno(out)) ? Mode::terminal : Mode::lines;
}

ProgressDisplay::ProgressDisplay(Mode mode, std::FILE* out) : mode_(mode), out_(out) {
  if (mode_ == Mode::terminal) redraw_ = std::thread([this] { redraw_loop(); });
}

ProgressDisplay::~ProgressDisplay() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (redraw_.joinable()) redraw_.join();
  // A stage an error ended: finish its line so the error starts on its own.
  if (!stage_.empty() && mode_ != Mode::quiet) std::fputs("\n", out_);
}

void ProgressDisplay::begin(const std::string& stage) {
  std::lock_guard lock(mutex_);
  stage_ = stage;
  start_ = std::chrono::steady_clock::now();
  if (mode_ == Mode::lines) std::fprintf(out_, "nanobake: %s... ", stage.c_str());
  if (mode_ == Mode::terminal) std::fprintf(out_, "\r\033[K%s", progress_line(stage, 0, 0, 0.0).c_str());
  std::fflush(out_);
}

void ProgressDisplay::end(const std::string& stage, double seconds) {
  std::lock_guard lock(mutex_);
  stage_.clear();
  if (mode_ == Mode::lines) std::fprintf(out_, "%.1f s\n", seconds);
  if (mode_ == Mode::terminal) std::fprintf(out_, "\r\033[Knanobake: %s  %.1f s\n", stage.c_str(), seconds);
  std::fflush(out_);
}

void ProgressDisplay::redraw_loop() {
  std::unique_lock lock(mutex_);
  while (!stopping_) {
    wake_.wait_for(lock, kRedrawEvery);
    if (stopping_ || stage_.empty()) continue;
    const auto [done, total] = progress::counts();
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::fprintf(out_, "\r\033[K%s", progress_line(stage_, done, total, elapsed).c_str());
    std::fflush(out_);
  }
}

}  // namespace nano::scene_bake
