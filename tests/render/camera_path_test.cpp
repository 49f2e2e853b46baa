// Camera paths: exact at keyframes, continuous and C¹ (finite differences), clamped outside the
// keyframes, strict parsing with errors naming file and key path, write → read bit for bit, and
// movie frame file names.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string_view>

#include <gtest/gtest.h>

#include "bake/scene/scene_parser.hpp"
#include "common/error.hpp"
#include "runtime/render/camera_path.hpp"

namespace {

using namespace nano;
using namespace nano::render;
using PathJson = nano::Json;
using namespace std::string_view_literals;

// Unequal key spacing, turning up vectors, a changing field of view, both key syntaxes.
PathJson sample_json() {
  return PathJson::parse(R"({"format": "nanouniverse-camera-path", "version": 1, "fps": 24, "keyframes": [
    {"time": 0, "camera": "pos=900,700,1300;at=0,0,0;up=0,1,0;fov=40"},
    {"time": 0.5, "position": [1200, -100, 600], "look_at": [50, 20, -10], "up": [0.2, 1, 0], "fov_degrees": 30},
    {"time": 2, "position": [-300, 400, 1500], "look_at": [0, 0, 0]},
    {"time": 2.25, "camera": "pos=-200,300,1200;up=1,0,0;fov=60"}]})");
}

CameraPath sample() { return parse_camera_path(sample_json(), "path.json"); }

double distance(const Camera& a, const Camera& b) {
  return glm::length(a.position - b.position) + glm::length(a.look_at - b.look_at) + glm::length(glm::normalize(a.up) - glm::normalize(b.up)) +
         std::abs(a.fov_degrees - b.fov_degrees);
}

TEST(CameraPath, ParsesBothSyntaxesAndInheritsLeftOutKeys) {
  const CameraPath p = sample();
  ASSERT_EQ(p.keyframes.size(), 4u);
  EXPECT_EQ(p.fps, 24);
  EXPECT_EQ(p.keyframes[1].camera.position, glm::dvec3(1200, -100, 600));
  EXPECT_EQ(p.keyframes[2].camera.up, glm::dvec3(0.2, 1, 0));  // kept from keyframe 1
  EXPECT_EQ(p.keyframes[2].camera.fov_degrees, 30);
  EXPECT_EQ(p.keyframes[3].camera.look_at, glm::dvec3(0, 0, 0));
  EXPECT_EQ(p.keyframes[3].camera.fov_degrees, 60);
  EXPECT_EQ(p.duration(), 2.25);
  EXPECT_EQ(p.frame_count(), 55u);  // floor(2.25 · 24) + 1
}

TEST(CameraPath, FrameCountSurvivesRounding) {
  CameraPath p;
  p.fps = 30;
  p.keyframes = {{0, {}}, {0.7, {}}};  // 0.7 · 30 = 20.999… in double
  EXPECT_EQ(p.frame_count(), 22u);
  p.keyframes.resize(1);
  EXPECT_EQ(p.frame_count(), 1u);
}

TEST(CameraPath, ExactAtKeyframes) {
  const CameraPath p = sample();
  for (const CameraKeyframe& k : p.keyframes) {
    const Camera c = camera_at(p, k.time);
    EXPECT_EQ(c.position, k.camera.position);
    EXPECT_EQ(c.look_at, k.camera.look_at);
    EXPECT_EQ(c.up, k.camera.up);
    EXPECT_EQ(c.fov_degrees, k.camera.fov_degrees);
  }
}

TEST(CameraPath, ClampsOutsideTheKeyframes) {
  CameraPath p = sample();
  EXPECT_EQ(distance(camera_at(p, -3), p.keyframes.front().camera), 0);
  EXPECT_EQ(distance(camera_at(p, 100), p.keyframes.back().camera), 0);
  EXPECT_EQ(distance(camera_at(p, std::nan("")), p.keyframes.front().camera), 0);
  // A path that starts later holds its first camera until then.
  p.keyframes[0].time = 0.25;
  EXPECT_EQ(distance(camera_at(p, 0.1), p.keyframes.front().camera), 0);
}

// Continuity: a small step in time moves the camera by a small amount everywhere, across keys too.
TEST(CameraPath, Continuous) {
  const CameraPath p = sample();
  const double h = 1e-7;
  for (double t = 0; t <= p.duration(); t += 0.01) {
    EXPECT_LT(distance(camera_at(p, t), camera_at(p, t + h)), 1e-2) << "t = " << t;
    EXPECT_LT(distance(camera_at(p, t - h), camera_at(p, t)), 1e-2) << "t = " << t;
  }
}

// C¹: at interior keyframes the one-sided derivatives of eye and target agree; inside segments
// the derivative is itself continuous (second differences stay bounded).
TEST(CameraPath, SmoothEyeAndTarget) {
  const CameraPath p = sample();
  const double h = 1e-6;
  for (std::size_t i = 1; i + 1 < p.keyframes.size(); ++i) {
    const double t = p.keyframes[i].time;
    const Camera c = camera_at(p, t), before = camera_at(p, t - h), after = camera_at(p, t + h);
    const glm::dvec3 eye_left = (c.position - before.position) / h, eye_right = (after.position - c.position) / h;
    const glm::dvec3 at_left = (c.look_at - before.look_at) / h, at_right = (after.look_at - c.look_at) / h;
    const double speed = glm::length(eye_left) + glm::length(at_left);
    EXPECT_GT(speed, 1.0);  // the test means something: the camera moves there
    EXPECT_LT(glm::length(eye_left - eye_right), 1e-3 * speed) << "keyframe " << i;
    EXPECT_LT(glm::length(at_left - at_right), 1e-3 * speed) << "keyframe " << i;
  }
  // Second derivative bounded (the cubic's), so the first has no jumps inside segments.
  const double k = 1e-3;
  for (double t = 0.01; t < p.duration() - 0.01; t += 0.013) {
    const glm::dvec3 second = (camera_at(p, t + k).position - 2.0 * camera_at(p, t).position + camera_at(p, t - k).position) / (k * k);
    EXPECT_LT(glm::length(second), 1e6) << "t = " << t;
  }
}

TEST(CameraPath, UpIsUnitAndFovBetweenKeys) {
  const CameraPath p = sample();
  for (double t = 0.013; t <= p.duration(); t += 0.05) {  // between keys: keys keep their own up
    const Camera c = camera_at(p, t);
    EXPECT_NEAR(glm::length(c.up), 1.0, 1e-12);
    EXPECT_GE(c.fov_degrees, 30 - 1e-12);
    EXPECT_LE(c.fov_degrees, 60 + 1e-12);
  }
}

TEST(CameraPath, TwoKeyframesMoveLinearly) {
  const CameraPath p = parse_camera_path(PathJson::parse(R"({"format": "nanouniverse-camera-path", "version": 1, "keyframes": [
    {"time": 0, "position": [0, 0, 100], "look_at": [0, 0, 0]}, {"time": 4, "position": [40, 0, 100], "look_at": [40, 0, 0]}]})"),
                                         "p.json");
  EXPECT_EQ(p.fps, 30);  // the default
  const Camera c = camera_at(p, 1);
  EXPECT_NEAR(c.position.x, 10, 1e-12);
  EXPECT_NEAR(c.look_at.x, 10, 1e-12);
}

void expect_error(const PathJson& j, const std::string& where, const std::string& part) {
  try {
    parse_camera_path(j, "movie.json");
    ADD_FAILURE() << "accepted: " << j.dump();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "movie.json");
    EXPECT_EQ(e.where(), where) << e.what();
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(CameraPath, StrictErrorsNameFileAndKeyPath) {
  PathJson j = sample_json();
  j["speed"] = 1;
  expect_error(j, "speed", "unknown key");
  j = sample_json(), j["format"] = "nanouniverse-scene";
  expect_error(j, "format", "nanouniverse-camera-path");
  j = sample_json(), j["version"] = 2;
  expect_error(j, "version", "expected 1");
  j = sample_json(), j["fps"] = 0;
  expect_error(j, "fps", "(0, 1000]");
  j = sample_json(), j["keyframes"] = PathJson::array();
  expect_error(j, "keyframes", "at least 1 element");
  j = sample_json(), j["keyframes"][1]["zoom"] = 2;
  expect_error(j, "keyframes[1].zoom", "unknown key");
  j = sample_json(), j["keyframes"][2]["time"] = 0.5;
  expect_error(j, "keyframes[2].time", "increase strictly");
  j = sample_json(), j["keyframes"][0]["time"] = -1;
  expect_error(j, "keyframes[0].time", ">= 0");
  j = sample_json(), j["keyframes"][1].erase("time");
  expect_error(j, "keyframes[1].time", "missing");
  j = sample_json(), j["keyframes"][1]["position"] = {1, 2};
  expect_error(j, "keyframes[1].position", "3 numbers");
  j = sample_json(), j["keyframes"][1]["fov_degrees"] = "wide";
  expect_error(j, "keyframes[1].fov_degrees", "a number in (0, 180)");
  j = sample_json(), j["keyframes"][1]["look_at"] = {1200, -100, 600};  // = position
  expect_error(j, "keyframes[1]", "same point");
  j = sample_json(), j["keyframes"][0]["camera"] = "pos=1,2;at=0,0,0";
  expect_error(j, "keyframes[0].camera", "three finite numbers");
  j = sample_json(), j["keyframes"][0]["position"] = {1, 2, 3};
  expect_error(j, "keyframes[0].position", "not both");
  j = sample_json(), j["keyframes"][1]["up"] = {0, -1, 0};
  expect_error(j, "keyframes[1].up", "180°");
  // Every keyframe valid, but the eye passes through the target between them, at frame 12.
  expect_error(PathJson::parse(R"({"format": "nanouniverse-camera-path", "version": 1, "fps": 24, "keyframes": [
    {"time": 0, "position": [-100, 0, 0], "look_at": [0, 0, 0]}, {"time": 1, "position": [100, 0, 0], "look_at": [0, 0, 0]}]})"),
               "keyframes", "frame 12");
}

TEST(CameraPath, WriteReadRoundTripIsExact) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "nano_camera_path_test";
  std::filesystem::create_directories(dir);
  CameraPath p = sample();
  p.keyframes[1].camera.position.x = 0.1 + 0.2;  // not a short decimal
  p.keyframes[2].time = 4.0 / 3.0;
  p.keyframes[2].camera.fov_degrees = std::nextafter(45.0, 90.0);
  const std::filesystem::path file = dir / "path.json";
  write_camera_path(file, p);
  const CameraPath q = read_camera_path(file);
  EXPECT_EQ(q.fps, p.fps);
  ASSERT_EQ(q.keyframes.size(), p.keyframes.size());
  for (std::size_t i = 0; i < p.keyframes.size(); ++i) {
    EXPECT_EQ(q.keyframes[i].time, p.keyframes[i].time);
    EXPECT_EQ(q.keyframes[i].camera.position, p.keyframes[i].camera.position);
    EXPECT_EQ(q.keyframes[i].camera.look_at, p.keyframes[i].camera.look_at);
    EXPECT_EQ(q.keyframes[i].camera.up, p.keyframes[i].camera.up);
    EXPECT_EQ(q.keyframes[i].camera.fov_degrees, p.keyframes[i].camera.fov_degrees);
  }
  // No temporary file is left beside it.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
  std::filesystem::remove_all(dir);
}

TEST(CameraPath, ReadErrorsNameTheFile) {
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "nano_camera_path_bad.json";
  std::ofstream(file) << "{\"format\": ";
  try {
    read_camera_path(file);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file.string());
    EXPECT_NE(std::string(e.what()).find("invalid JSON"), std::string::npos) << e.what();
  }
  std::filesystem::remove(file);
  EXPECT_THROW(read_camera_path(file), InputError);
}

// scene.json's camera and a camera path's keyframe are read by one reader (common/json_cursor.hpp):
// the same malformed camera is refused by both, in the same words, each naming its own file and
// the key path (camera.* in the scene, keyframes[0].* in the path).
TEST(CameraPath, RefusesWhatTheSceneReaderRefusesInTheSameWords) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "nano_camera_path_shared_reader";
  std::filesystem::create_directories(dir);
  const std::filesystem::path scene_file = dir / "scene.json", path_file = dir / "path.json";
  const auto refusal = [](const auto& read, const std::filesystem::path& file) {
    try {
      read(file);
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), file.string()) << e.what();
      return e;
    }
    ADD_FAILURE() << file << " was accepted";
    return InputError("", "", "");
  };
  struct Case {
    std::string_view camera;  // the members of the camera object
    const char* where;   // the key path below it; empty: a line:column
    const char* rule;    // what both errors say (a prefix of it)
  };
  const Case cases[] = {
      {R"("position": [1, 2], "look_at": [0, 0, 0])", ".position", "expected an array of 3 numbers [x, y, z], got [1,2]"},
      {R"("position": [0, 0, 9], "look_at": [0, "a", 0])", ".look_at[1]", "expected a number, got \"a\""},
      {R"("position": [0, 0, 9], "look_at": [0, 0, 0], "fov_degrees": 180)", ".fov_degrees", "expected a number in (0, 180), got 180"},
      {R"("position": [0, 0, 9], "look_at": [0, 0, 0], "fov_degrees": 1e400)", ".fov_degrees", ""},
      {R"("position": [0, 0, 9], "position": [0, 0, 8], "look_at": [0, 0, 0])", ".position", "key \"position\" appears more than once"},
      {R"("position": [0, 0, 9], "look_at": [0, 0, 0], "zoom": 2)", ".zoom", "unknown key; allowed here: "},
      {R"("position": [0, 0, 9],, "look_at": [0, 0, 0])", "", "invalid JSON: "},
      {"\"position\": [0, 0, 9], \"look_at\": [0, 0, 0], \"up\": [0, 1, 0\0]"sv, "", "a NUL byte"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.camera);
    std::ofstream(scene_file, std::ios::binary)
        << R"({"format": "nanouniverse-scene", "version": 1, "molecules": {"hb": {"file": "h.pdb"}},
              "solubles": {"lumen": {"cube_size": 100, "molecules": [{"molecule": "hb", "concentration_mM": 1}]}},
              "compartments": {"cell": {"mesh": {"generate": "sphere", "triangles": 1000, "radius": 500}, "soluble": "lumen"}},
              "instances": [{"compartment": "cell"}],
              "camera": {)"
        << c.camera << "}}";
    std::ofstream(path_file, std::ios::binary)
        << R"({"format": "nanouniverse-camera-path", "version": 1, "keyframes": [{"time": 0, )" << c.camera << "}]}";
    const InputError in_scene = refusal([](const auto& f) { nano::scene::load_scene_description(f); }, scene_file);
    const InputError in_path = refusal([](const auto& f) { read_camera_path(f); }, path_file);
    if (*c.where) {
      EXPECT_EQ(in_scene.where(), std::string("camera") + c.where);
      EXPECT_EQ(in_path.where(), std::string("keyframes[0]") + c.where);
    } else {  // a syntax error: its line and column
      EXPECT_NE(in_scene.where().find(':'), std::string::npos) << in_scene.what();
      EXPECT_NE(in_path.where().find(':'), std::string::npos) << in_path.what();
    }
    EXPECT_EQ(std::string(in_scene.rule()).rfind(c.rule, 0), 0u) << in_scene.what();
    EXPECT_EQ(std::string(in_path.rule()).rfind(c.rule, 0), 0u) << in_path.what();
    if (std::string_view(c.rule).find("unknown key") == std::string_view::npos) {  // the allowed keys differ
      EXPECT_EQ(std::string(in_scene.rule()), std::string(in_path.rule()));
    }
  }
  std::filesystem::remove_all(dir);
}

TEST(FramePattern, FormatsAndRejects) {
  EXPECT_EQ(frame_file_name("frames/%05d.png", 42), "frames/00042.png");
  EXPECT_EQ(frame_file_name("f%d.png", 1234567), "f1234567.png");
  EXPECT_EQ(frame_file_name("%3d", 7), "  7");
  EXPECT_EQ(frame_file_name("100%%/%02d%%.png", 3), "100%/03%.png");
  EXPECT_EQ(frame_file_name("%03d", 12345), "12345");
  for (const char* bad : {"out.png", "%d_%d.png", "%s.png", "%x.png", "%5.2d", "%ld.png", "%", "a%", "%-5d", "%021d", "%%d"}) {
    try {
      check_frame_pattern(bad, "--depth");
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const nano::InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(std::string("--depth: '") + bad + "'", 0), 0u) << e.what();
    }
  }
  EXPECT_NO_THROW(check_frame_pattern("%020d", "--depth"));
  EXPECT_THROW((void)frame_file_name("out.png", 1), std::logic_error);  // patterns are checked first
}

}  // namespace
