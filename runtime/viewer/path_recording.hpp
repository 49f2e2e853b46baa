#pragma once
// Camera paths in the viewer: recording keyframes (K, the panel, the script's `keyframe`), saving
// and loading them in the JSON of runtime/render/camera_path.hpp, and showing the path at a time
// the way `nanoview render --path` renders it. Free of any window, so the panel, the keys and the
// script runner share one implementation that is tested without a display.
#include <cstdint>
#include <optional>
#include <string>

#include "runtime/render/camera_path.hpp"
#include "runtime/render/camera_spec.hpp"

namespace nano::viewer {

struct ViewerState;

struct PathRecording {
  render::CameraPath path;                // no keyframes until one is added or a path is loaded
  double step = 2;                        // s: K puts the next keyframe this long after the last
  std::string file = "camera-path.json";  // the panel's file for "Save path" and "Load path"
  std::optional<double> play_time;        // path time (s) while the path plays in the window
};

// When K adds the next keyframe: 0 for the first, otherwise the last keyframe's time + `step`.
double next_keyframe_time(const render::CameraPath& path, double step);

// Appends `camera` at `time` (s). Throws an InputError against `source` (the script line or the
// key that asked), leaving the path unchanged, when
// the time does not come after the last keyframe or the path would no longer save (the up vector
// turns by 180°, the spline passes the eye through the target, too many frames): a recording is
// always one that `render --path` accepts.
void add_keyframe(render::CameraPath& path, const Camera& camera, double time, const InputSource& source);

// Time of frame `frame` (k / fps). Throws an InputError against `source` when there is no path or
// the frame lies past its last.
double path_frame_time(const render::CameraPath& path, std::uint64_t frame, const InputSource& source);

// Sets the camera to camera_at(path, time) and the effect time to `time`, exactly what `render
// --path` uses for a frame at that time, so animation plays along with the camera.
void show_path_at(ViewerState& state, double time);

// Playback in the window. start_playback shows time 0 (throws an InputError against `source` without
// keyframes) and pauses the free-running animation clock, which the path now drives;
// advance_playback moves on by `seconds` of wall-clock time and returns whether it still plays
// (at the end it shows the last keyframe and stops; a degenerate camera between frame times stops
// it with a status line instead of throwing). stop_playback leaves the camera where it is.
void start_playback(ViewerState& state, const InputSource& source);
bool advance_playback(ViewerState& state, double seconds);
void stop_playback(ViewerState& state);

// The K/L keys and the panel's buttons: these never throw; what happened (or why not) goes to
// state.status, because an interactive mistake must not end the session.
void record_keyframe(ViewerState& state);  // the current camera at next_keyframe_time
void toggle_playback(ViewerState& state);
void save_recording(ViewerState& state);   // to state.path.file, atomically
void load_recording(ViewerState& state);   // from state.path.file; replaces the keyframes
void clear_recording(ViewerState& state);

}  // namespace nano::viewer
