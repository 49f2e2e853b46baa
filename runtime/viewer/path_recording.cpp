#include "runtime/viewer/path_recording.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "common/error.hpp"
#include "runtime/viewer/viewer_state.hpp"

namespace nano::viewer {
namespace {

std::string seconds_text(double seconds) {
  std::ostringstream s;
  s << seconds << " s";
  return s.str();
}

std::string summary(const render::CameraPath& path) {
  return std::to_string(path.keyframes.size()) + " keyframe(s), " + seconds_text(path.duration()) + ", " +
         std::to_string(path.frame_count()) + " frame(s) at " + std::to_string(int(std::lround(path.fps))) + " fps";
}

// The K/L keys and the panel's buttons: their refusals go to the status line, which needs no source.
const InputSource kInteractive{"viewer"};

}  // namespace

double next_keyframe_time(const render::CameraPath& path, double step) {
  return path.keyframes.empty() ? 0.0 : path.keyframes.back().time + step;
}

void add_keyframe(render::CameraPath& path, const Camera& camera, double time, const InputSource& source) {
  if (!std::isfinite(time) || time < 0) source.fail("a keyframe time is seconds ≥ 0, got " + seconds_text(time));
  if (!path.keyframes.empty() && !(time > path.keyframes.back().time))
    source.fail("keyframe times must increase: " + seconds_text(time) + " does not come after the last keyframe's " +
                seconds_text(path.keyframes.back().time));
  render::CameraPath candidate = path;
  candidate.keyframes.push_back({time, camera});
  // The reader's rules, applied now: a recording that could not be saved (or rendered) would only
  // surface as an error after the user has stopped recording.
  try {
    (void)render::parse_camera_path(render::to_json(candidate), "");
  } catch (const InputError& e) {
    // The reader's error names a file that does not exist yet; say which keyframe it refuses.
    source.fail("keyframe at " + seconds_text(time) + " rejected: " + (e.where().empty() ? "" : e.where() + ": ") + e.rule());
  }
  path = std::move(candidate);
}

double path_frame_time(const render::CameraPath& path, std::uint64_t frame, const InputSource& source) {
  if (path.keyframes.empty()) source.fail("no camera path: add keyframes or load a path first");
  if (frame >= path.frame_count())
    source.fail("frame " + std::to_string(frame) + " is past the path's last frame " + std::to_string(path.frame_count() - 1));
  return path.frame_time(frame);
}

void show_path_at(ViewerState& state, double time) {
  state.camera.set_camera(render::camera_at(state.path.path, time));
  state.settings.effects.time = time;
  state.touch();
}

void start_playback(ViewerState& state, const InputSource& source) {
  if (state.path.path.keyframes.empty()) source.fail("no camera path to play: add keyframes (K) or load one");
  state.playing = false;
  state.path.play_time = 0.0;
  show_path_at(state, 0.0);
}

bool advance_playback(ViewerState& state, double seconds) {
  if (!state.path.play_time) return false;
  const double time = *state.path.play_time + std::max(seconds, 0.0);
  const double end = state.path.path.duration();
  try {
    if (time >= end) {
      show_path_at(state, end);
      state.path.play_time.reset();
      state.status = "path played to its end (" + seconds_text(end) + ")";
      return false;
    }
    show_path_at(state, time);
  } catch (const std::invalid_argument& e) {
    // Reading a path checks the camera at every frame time; wall-clock playback also visits the
    // times between, where the spline could (just) pass the eye through the target.
    state.path.play_time.reset();
    state.status = "path playback stopped at " + seconds_text(time) + ": " + e.what();
    return false;
  }
  state.path.play_time = time;
  return true;
}

void stop_playback(ViewerState& state) { state.path.play_time.reset(); }

void record_keyframe(ViewerState& state) {
  PathRecording& r = state.path;
  try {
    add_keyframe(r.path, state.camera.camera(), next_keyframe_time(r.path, r.step), kInteractive);
    // The camera too: the session log then holds the recording in the syntax --camera reads.
    state.status = "keyframe " + std::to_string(r.path.keyframes.size()) + " at " + seconds_text(r.path.duration()) + ": " +
                   r.path.keyframes.back().camera.to_string();
  } catch (const InputError& e) {
    state.status = e.rule();
  }
}

void toggle_playback(ViewerState& state) {
  if (state.path.play_time) {
    stop_playback(state);
    state.status = "path playback stopped";
    return;
  }
  try {
    start_playback(state, kInteractive);
    state.status = "playing the path: " + summary(state.path.path);
  } catch (const InputError& e) {
    state.status = e.rule();
  }
}

void save_recording(ViewerState& state) {
  const PathRecording& r = state.path;
  if (r.path.keyframes.empty()) {
    state.status = "no keyframes to save: add some with K";
    return;
  }
  try {
    render::write_camera_path(r.file, r.path);
    state.status = "saved " + r.file + ": " + summary(r.path);
  } catch (const std::exception& e) {
    state.status = std::string("saving the path failed: ") + e.what();
  }
}

void load_recording(ViewerState& state) {
  try {
    render::CameraPath path = render::read_camera_path(state.path.file);
    stop_playback(state);
    state.path.path = std::move(path);
    state.status = "loaded " + state.path.file + ": " + summary(state.path.path);
  } catch (const std::exception& e) {
    state.status = std::string("loading the path failed: ") + e.what();
  }
}

void clear_recording(ViewerState& state) {
  stop_playback(state);
  state.path.path.keyframes.clear();
  state.status = "camera path cleared";
}

}  // namespace nano::viewer
