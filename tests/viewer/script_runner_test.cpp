// The script runner against a fake host: state changes, frames, picks, screenshots, camera paths
// (record, save, load, frames), and errors found while running that still name the script's line.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "runtime/render/camera_path.hpp"
#include "runtime/viewer/script_runner.hpp"

namespace nano::viewer {
namespace {

class FakeHost : public ScriptHost {
public:
  FakeHost() : state_(CameraController(Camera{}, 1000), render::RenderSettings{}) {}
  ViewerState& state() override { return state_; }
  void render_frames(std::uint32_t count) override {
    frames += count;
    frame_.width = width, frame_.height = height;
    frame_.hits.assign(std::size_t(width) * height, gpu::PixelHit{});
    for (std::size_t i = 0; i < frame_.hits.size(); ++i) frame_.hits[i].atom = std::uint32_t(i);
    frame_.rgba.assign(frame_.hits.size(), 0xFF336699u);
    version = state_.version;
  }
  const render::Frame& current_frame() override {
    if (version != state_.version || frame_.width != width) render_frames(1);
    return frame_;
  }
  std::span<const std::uint32_t> current_image() override { return current_frame().rgba; }
  void resize(std::uint32_t w, std::uint32_t h) override { width = w, height = h; }
  nlohmann::json describe(const gpu::PixelHit& hit) override { return {{"hit", true}, {"atom", hit.atom}}; }

  ViewerState state_;
  render::Frame frame_;
  std::uint32_t width = 8, height = 4, frames = 0;
  std::uint64_t version = ~0ull;
};

void run(const std::string& text, FakeHost& host, std::ostream& out) {
  const Script script = parse_script(text, "run.txt");
  for (const auto& c : script.commands)
    if (!run_command(c, script.file, host, out)) break;
}

TEST(ScriptRunner, ChangesStateAndRendersFrames) {
  FakeHost host;
  std::ostringstream out;
  run("camera pos=0,0,500;fov=30\nclip plane 0,0,1,0\nclip box -1,-1,-1,1,1,1\neffect ao on\ntime 3\nwait 2\n", host, out);
  const auto& s = host.state_;
  EXPECT_EQ(s.camera.camera().position, glm::dvec3(0, 0, 500));
  EXPECT_EQ(s.camera.camera().fov_degrees, 30);
  EXPECT_TRUE(s.settings.effects.flag(EffectId::clipping));
  EXPECT_EQ(s.settings.effects.clipping.planes.size(), 1u);
  EXPECT_TRUE(s.settings.effects.clipping.box.has_value());
  EXPECT_TRUE(s.settings.effects.flag(EffectId::ambient_occlusion));
  EXPECT_EQ(s.settings.effects.time, 3);
  EXPECT_EQ(host.frames, 2u);
  run("clip off\n", host, out);
  EXPECT_FALSE(host.state_.settings.effects.flag(EffectId::clipping));
  EXPECT_TRUE(host.state_.settings.effects.clipping.planes.empty());
  EXPECT_FALSE(host.state_.settings.effects.clipping.box.has_value());
}

// `preset illustrative` turns its effects on with the preset's values; an `effect ... off` after it
// still switches one of them off.
TEST(ScriptRunner, PresetTurnsItsEffectsOnWithItsValues) {
  FakeHost host;
  std::ostringstream out;
  run("preset illustrative\neffect fog off\n", host, out);
  const render::EffectSettings& e = host.state_.settings.effects;
  for (const PresetEffect& effect : find_preset("illustrative")->effects) {
    EXPECT_EQ(e.flag(effect.id), effect.id != EffectId::fog) << effect_declaration(effect.id).name;
    const auto parameters = effect_declaration(effect.id).parameters;
    for (std::size_t i = 0; i < parameters.size(); ++i) {
      if (parameters[i].kind == ParameterKind::colour) EXPECT_EQ(colour_slot(e.record, parameters[i]), pack_colour(effect.values[i]));
      else EXPECT_EQ(number_slot(e.record, parameters[i]), float(effect.values[i].x)) << parameters[i].key;
    }
  }
  EXPECT_FALSE(e.flag(EffectId::shadows));
}

TEST(ScriptRunner, ShowAndHideSwitchTheMediumAndNamesInTheSettings) {
  FakeHost host;
  std::ostringstream out;
  run("hide medium\nhide rbc\nhide POPC\nhide rbc\n", host, out);
  const render::RenderSettings& s = host.state_.settings;
  EXPECT_FALSE(s.show_medium);
  EXPECT_EQ(s.hidden, (std::vector<std::string>{"POPC", "rbc"}));  // hidden once, however often asked
  EXPECT_FALSE(render::shown(s, "rbc"));
  EXPECT_TRUE(render::shown(s, "albumin"));
  run("show medium\nshow rbc\n", host, out);
  EXPECT_TRUE(host.state_.settings.show_medium);
  EXPECT_EQ(host.state_.settings.hidden, std::vector<std::string>{"POPC"});
}

TEST(ScriptRunner, PickPrintsOneJsonLine) {
  FakeHost host;
  std::ostringstream out;
  run("size 8x4\npick 3 2\npick 0 0\n", host, out);
  std::istringstream lines(out.str());
  std::string line;
  ASSERT_TRUE(std::getline(lines, line));
  const auto j = nlohmann::json::parse(line);
  EXPECT_EQ(j["x"], 3);
  EXPECT_EQ(j["y"], 2);
  EXPECT_EQ(j["atom"], 2 * 8 + 3);
  ASSERT_TRUE(std::getline(lines, line));
  EXPECT_EQ(nlohmann::json::parse(line)["atom"], 0);
  EXPECT_FALSE(std::getline(lines, line));
  EXPECT_EQ(host.frames, 1u);  // both picks read the same full frame
  ASSERT_TRUE(host.state_.last_pick.has_value());
}

TEST(ScriptRunner, QuitStops) {
  FakeHost host;
  std::ostringstream out;
  run("wait 1\nquit\nwait 5\n", host, out);
  EXPECT_EQ(host.frames, 1u);
}

TEST(ScriptRunner, ScreenshotWritesPngAndIds) {
  FakeHost host;
  std::ostringstream out;
  const auto dir = std::filesystem::temp_directory_path() / ("viewer_runner_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  run("size 5x3\nscreenshot " + (dir / "shot.png").string() + "\n", host, out);
  EXPECT_TRUE(std::filesystem::exists(dir / "shot.png"));
  ASSERT_TRUE(std::filesystem::exists(dir / "shot.ids"));
  EXPECT_EQ(std::filesystem::file_size(dir / "shot.ids"), 16u + 5 * 3 * sizeof(gpu::PixelHit));
  std::filesystem::remove_all(dir);
}

std::filesystem::path temp_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(ScriptRunner, RecordsSavesLoadsAndShowsPathFrames) {
  FakeHost host;
  std::ostringstream out;
  const auto dir = temp_dir("viewer_runner_path");
  const std::string file = (dir / "cam.json").string();
  run("camera pos=0,0,900;at=0,0,0;up=0,1,0;fov=40\nkeyframe 0\n"
      "camera pos=600,0,600;fov=30\nkeyframe 2\n"
      "camera pos=900,100,0\nkeyframe 4\n"
      "path save " + file + "\n",
      host, out);
  auto& s = host.state_;
  ASSERT_EQ(s.path.path.keyframes.size(), 3u);
  EXPECT_EQ(s.path.path.keyframes[1].time, 2.0);
  EXPECT_EQ(s.path.path.keyframes[1].camera.position, glm::dvec3(600, 0, 600));
  EXPECT_EQ(s.path.path.keyframes[2].camera.fov_degrees, 30);  // left out: kept from the camera
  EXPECT_EQ(host.frames, 0u);  // recording renders nothing

  // What render --path reads back is what was recorded, bit for bit.
  const render::CameraPath saved = render::read_camera_path(file);
  ASSERT_EQ(saved.keyframes.size(), 3u);
  EXPECT_EQ(saved.keyframes[2].camera.position, s.path.path.keyframes[2].camera.position);
  EXPECT_EQ(saved.fps, 30);

  run("path clear\n", host, out);
  EXPECT_TRUE(s.path.path.keyframes.empty());
  const std::uint64_t before = s.version;
  run("path load " + file + "\npath frame 1\n", host, out);
  ASSERT_EQ(s.path.path.keyframes.size(), 3u);
  // Frame 1 is at 1/30 s: the camera and the effect time render --path --frames 1:1 uses.
  const Camera expected = render::camera_at(saved, 1.0 / 30);
  EXPECT_EQ(s.camera.camera().position, expected.position);
  EXPECT_EQ(s.camera.camera().look_at, expected.look_at);
  EXPECT_EQ(s.camera.camera().fov_degrees, expected.fov_degrees);
  EXPECT_EQ(s.settings.effects.time, 1.0 / 30);
  EXPECT_GT(s.version, before);  // the frame must be rendered again

  run("path frame 120\n", host, out);  // the last frame: the last keyframe exactly
  EXPECT_EQ(s.camera.camera().position, glm::dvec3(900, 100, 0));
  EXPECT_EQ(s.settings.effects.time, 4.0);

  run("path play 10 14\n", host, out);
  EXPECT_EQ(host.frames, 5u);  // one full frame each
  EXPECT_EQ(s.settings.effects.time, 14.0 / 30);
  std::filesystem::remove_all(dir);
}

void expect_run_error(const std::string& text, const std::string& line, const std::string& fragment) {
  FakeHost host;
  std::ostringstream out;
  try {
    run(text, host, out);
    FAIL() << "no error for: " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "run.txt");
    EXPECT_EQ(e.where(), line) << text;
    EXPECT_NE(e.rule().find(fragment), std::string::npos) << "'" << e.rule() << "' lacks '" << fragment << "'";
  }
}

TEST(ScriptRunner, ErrorsWhileRunningNameTheLine) {
  // The default camera is at (0, 0, 1000): moving the target there makes it degenerate.
  expect_run_error("wait 1\ncamera at=0,0,1000\n", "line 2", "same point");
  std::string nine;
  for (int i = 0; i < 9; ++i) nine += "clip plane 1,0,0," + std::to_string(i) + "\n";
  expect_run_error(nine, "line 9", "at most 8");
  expect_run_error("size 8x4\npick 8 0\n", "line 2", "outside the 8x4 frame");
  expect_run_error("screenshot /nonexistent/dir/a.png\n", "line 1", "/nonexistent/dir/a");
}

TEST(ScriptRunner, PathErrorsNameTheLine) {
  expect_run_error("keyframe 2\nkeyframe 2\n", "line 2", "times must increase");
  expect_run_error("keyframe 2\nkeyframe 1\n", "line 2", "does not come after");
  // Up turned by 180° between keyframes has no interpolation; the path would not read back.
  expect_run_error("keyframe 0\ncamera up=0,-1,0\nkeyframe 1\n", "line 3", "180°");
  expect_run_error("keyframe 0\nkeyframe 1000000\n", "line 2", "frames");
  expect_run_error("path save x.json\n", "line 1", "no keyframes");
  expect_run_error("keyframe 0\npath save /nonexistent/dir/p.json\n", "line 2", "/nonexistent/dir/p.json");
  expect_run_error("path load /nonexistent/p.json\n", "line 1", "/nonexistent/p.json");
  expect_run_error("path frame 0\n", "line 1", "no camera path");
  expect_run_error("keyframe 0\ncamera pos=0,0,500\nkeyframe 1\npath frame 31\n", "line 4", "past the path's last frame 30");
  expect_run_error("keyframe 0\npath play 0 1\n", "line 2", "past the path's last frame 0");
  expect_run_error("wait 1\npath clear\npath play 0 0\n", "line 3", "no camera path");
}

TEST(ScriptRunner, BadPathFileNamesFileAndLine) {
  const auto dir = temp_dir("viewer_runner_bad_path");
  const std::string file = (dir / "bad.json").string();
  std::ofstream(file) << R"({"format": "nanouniverse-camera-path", "version": 1, "keyframes": [{"time": -1}]})";
  FakeHost host;
  std::ostringstream out;
  try {
    run("wait 1\npath load " + file + "\n", host, out);
    FAIL() << "a bad path file was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "run.txt");
    EXPECT_EQ(e.where(), "line 2");
    EXPECT_NE(e.rule().find(file + ":keyframes[0].time"), std::string::npos) << e.rule();
  }
  std::filesystem::remove_all(dir);
}

TEST(ScriptRunner, IdsPathBesideThePng) {
  EXPECT_EQ(ids_path_for("out/a.png"), "out/a.ids");
  EXPECT_EQ(ids_path_for("shot"), "shot.ids");
}

}  // namespace
}  // namespace nano::viewer
