// Camera-path recording and playback in the viewer, without a window: keyframe times and checks,
// playback in wall-clock time (camera and effect time as `render --path` has them), and the
// K/L/panel actions, which report into the status line instead of throwing.
#include <filesystem>

#include <gtest/gtest.h>

#include "runtime/render/camera_path.hpp"
#include "runtime/viewer/path_recording.hpp"
#include "runtime/viewer/viewer_state.hpp"

namespace nano::viewer {
namespace {

Camera camera_at_eye(const glm::dvec3& eye) {
  Camera c;
  c.position = eye;
  return c;
}

ViewerState make_state() { return ViewerState(CameraController(Camera{}, 1000), render::RenderSettings{}); }

// Where the action came from, as a script line names it.
const InputSource kLine{"tour.nvs", "line 7"};

// The error of `action`, which must be an InputError naming kLine.
template <class F>
std::string refusal(F&& action) {
  try {
    action();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), kLine.file) << e.what();
    EXPECT_EQ(e.where(), kLine.where) << e.what();
    return e.rule();
  }
  ADD_FAILURE() << "accepted";
  return {};
}

TEST(PathRecording, KeyframeTimesFollowTheStep) {
  render::CameraPath path;
  EXPECT_EQ(next_keyframe_time(path, 2), 0.0);
  add_keyframe(path, camera_at_eye({0, 0, 900}), 0, kLine);
  EXPECT_EQ(next_keyframe_time(path, 2), 2.0);
  add_keyframe(path, camera_at_eye({500, 0, 500}), 1.5, kLine);
  EXPECT_EQ(next_keyframe_time(path, 0.5), 2.0);
  EXPECT_EQ(path.keyframes.size(), 2u);
}

TEST(PathRecording, RejectedKeyframesLeaveThePathAlone) {
  render::CameraPath path;
  add_keyframe(path, camera_at_eye({0, 0, 900}), 1, kLine);
  EXPECT_NE(refusal([&] { add_keyframe(path, camera_at_eye({0, 0, 800}), 1, kLine); }).find("must increase"), std::string::npos);
  EXPECT_NE(refusal([&] { add_keyframe(path, camera_at_eye({0, 0, 800}), -1, kLine); }).find("seconds ≥ 0"), std::string::npos);
  EXPECT_NE(refusal([&] { add_keyframe(path, camera_at_eye({0, 0, 800}), std::nan(""), kLine); }).find("seconds ≥ 0"),
            std::string::npos);
  Camera flipped = camera_at_eye({0, 0, 800});
  flipped.up = {0, -1, 0};
  EXPECT_NE(refusal([&] { add_keyframe(path, flipped, 2, kLine); }).find("keyframe at 2 s rejected"), std::string::npos);
  EXPECT_EQ(path.keyframes.size(), 1u);
}

TEST(PathRecording, FrameTimes) {
  render::CameraPath path;
  EXPECT_NE(refusal([&] { (void)path_frame_time(path, 0, kLine); }).find("no camera path"), std::string::npos);
  add_keyframe(path, camera_at_eye({0, 0, 900}), 0, kLine);
  add_keyframe(path, camera_at_eye({900, 0, 0}), 1, kLine);
  EXPECT_EQ(path_frame_time(path, 0, kLine), 0.0);
  EXPECT_EQ(path_frame_time(path, 30, kLine), 1.0);
  EXPECT_NE(refusal([&] { (void)path_frame_time(path, 31, kLine); }).find("past the path's last frame 30"), std::string::npos);
}

TEST(PathRecording, PlaybackFollowsTheWallClockAndStopsAtTheEnd) {
  ViewerState s = make_state();
  EXPECT_NE(refusal([&] { start_playback(s, kLine); }).find("no camera path to play"), std::string::npos);
  add_keyframe(s.path.path, camera_at_eye({0, 0, 900}), 0, kLine);
  add_keyframe(s.path.path, camera_at_eye({900, 0, 0}), 2, kLine);
  s.playing = true;
  start_playback(s, kLine);
  EXPECT_FALSE(s.playing);  // the path drives the effect time now
  EXPECT_EQ(s.camera.camera().position, glm::dvec3(0, 0, 900));
  const std::uint64_t version = s.version;
  EXPECT_TRUE(advance_playback(s, 0.5));
  EXPECT_GT(s.version, version);
  EXPECT_EQ(s.settings.effects.time, 0.5);
  EXPECT_EQ(s.camera.camera().position, render::camera_at(s.path.path, 0.5).position);
  EXPECT_FALSE(advance_playback(s, 5));  // past the end: the last keyframe, then stop
  EXPECT_FALSE(s.path.play_time.has_value());
  EXPECT_EQ(s.camera.camera().position, glm::dvec3(900, 0, 0));
  EXPECT_EQ(s.settings.effects.time, 2.0);
  EXPECT_FALSE(advance_playback(s, 1));  // not playing: nothing changes
  EXPECT_EQ(s.settings.effects.time, 2.0);
}

TEST(PathRecording, InteractiveActionsReportInsteadOfThrowing) {
  ViewerState s = make_state();
  const auto dir = std::filesystem::temp_directory_path() / ("viewer_path_actions_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  s.path.file = (dir / "p.json").string();

  save_recording(s);
  EXPECT_NE(s.status.find("no keyframes"), std::string::npos) << s.status;
  toggle_playback(s);
  EXPECT_NE(s.status.find("no camera path"), std::string::npos) << s.status;

  record_keyframe(s);  // at 0
  s.camera.set_camera(camera_at_eye({700, 0, 700}));
  s.path.step = 1.5;
  record_keyframe(s);  // at 1.5
  ASSERT_EQ(s.path.path.keyframes.size(), 2u);
  EXPECT_EQ(s.path.path.keyframes[1].time, 1.5);
  EXPECT_NE(s.status.find("keyframe 2"), std::string::npos) << s.status;

  save_recording(s);
  EXPECT_NE(s.status.find("saved"), std::string::npos) << s.status;
  EXPECT_EQ(render::read_camera_path(s.path.file).keyframes.size(), 2u);

  toggle_playback(s);
  EXPECT_TRUE(s.path.play_time.has_value());
  toggle_playback(s);
  EXPECT_FALSE(s.path.play_time.has_value());

  clear_recording(s);
  EXPECT_TRUE(s.path.path.keyframes.empty());
  load_recording(s);
  EXPECT_EQ(s.path.path.keyframes.size(), 2u) << s.status;

  s.path.file = (dir / "missing.json").string();
  load_recording(s);
  EXPECT_NE(s.status.find("missing.json"), std::string::npos) << s.status;
  EXPECT_EQ(s.path.path.keyframes.size(), 2u);  // a failed load keeps the path
  s.path.file = (dir / "no" / "dir" / "p.json").string();
  save_recording(s);
  EXPECT_NE(s.status.find("failed"), std::string::npos) << s.status;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace nano::viewer
