#pragma once
// What the panel, the script runner and the main loop share: the camera, the render settings and
// what the last frames measured. Every change of something a frame depends on goes through
// touch(), so the loop knows when its last full-resolution frame no longer shows the state.
#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "runtime/render/renderer.hpp"
#include "runtime/viewer/camera_controller.hpp"
#include "runtime/viewer/path_recording.hpp"

namespace nano::viewer {

struct FrameStats {
  double seconds = 0;          // last frame: µLAS rebuild + dispatch + read-back
  double rays_per_second = 0;  // primary + shadow + AO rays of the last frame / its time
  std::uint32_t width = 0, height = 0;
  std::uint32_t scale = 1;     // 1: full resolution; k: rendered at 1/k per axis while moving
  std::uint32_t samples = 0;   // frames averaged into what is shown
};

struct ViewerState {
  ViewerState(CameraController camera, const render::RenderSettings& settings)
      : camera(std::move(camera)), settings(settings) {}

  CameraController camera;
  render::RenderSettings settings;  // effects included; sample_index is the loop's business
  std::uint64_t version = 0;        // bumped by touch()
  void touch() { ++version; }

  std::uint32_t ao_samples = 16;    // frames averaged while the camera rests with AO on
  double motion_budget = 0.1;       // seconds per frame allowed while moving
  double rest_step_budget = 0.3;    // at rest: seconds a refinement step may take (see rest_scale)
  bool playing = false;             // animation time advances with the wall clock
  double play_speed = 1;
  PathRecording path;               // keyframes recorded or loaded, and their playback

  FrameStats stats;
  std::optional<nlohmann::json> last_pick;  // describe_hit + "x", "y"
  std::string status;                       // one line: last screenshot written, last error
  std::string compiling;                    // "compiling ao… 3 s" while a pipeline is built off the frame path
  bool screenshot_requested = false;
};

}  // namespace nano::viewer
