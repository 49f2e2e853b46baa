#pragma once
// Camera paths for movies: keyframed cameras in a JSON file, evaluated at any time.
//
//   {"format": "nanouniverse-camera-path", "version": 1, "fps": 30,
//    "keyframes": [{"time": 0, "camera": "position=x,y,z;look_at=x,y,z;up=x,y,z;fov_degrees=DEG"},
//                  {"time": 2.5, "position": [x, y, z], "look_at": [x, y, z], "up": [x, y, z], "fov_degrees": 40}]}
//
// The "camera" string is the --camera form (camera_spec.hpp, where pos, at and fov are aliases, so
// older paths still read). Times are seconds ≥ 0, strictly increasing. Keys a keyframe leaves out
// keep the previous keyframe's values (Camera's defaults for the first). Frame k is at time k / fps,
// so a movie starts at time 0 and ends at the last keyframe; before the first keyframe the camera
// holds still. Position and look_at follow a C¹ cubic Hermite spline in time with Catmull–Rom tangents (one-sided at
// the ends), up is a normalised lerp and the field of view a lerp between neighbouring keys; each
// keyframe is reached exactly.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "common/json_document.hpp"
#include "runtime/render/camera_spec.hpp"

namespace nano::render {

struct CameraKeyframe {
  double time = 0;  // s
  Camera camera;
};

struct CameraPath {
  double fps = 30;
  std::vector<CameraKeyframe> keyframes;  // at least one

  double duration() const { return keyframes.empty() ? 0.0 : keyframes.back().time; }
  // floor(duration · fps) + 1: frames 0 … frame_count() − 1 at times k / fps.
  std::uint64_t frame_count() const;
  double frame_time(std::uint64_t frame) const { return double(frame) / fps; }
};

// Strict: unknown keys, wrong types, times that do not increase, invalid cameras (also between
// keyframes, at every frame time) throw InputError naming `file` and the key path (keyframes[2].up).
// Read with the scene file's reader (common/json_cursor.hpp), so the two word their errors alike.
CameraPath parse_camera_path(const Json& json, const std::string& file);
// The file is read as scene.json is (common/json_document.hpp): line:column syntax errors,
// duplicate keys refused, the same limits against hostile files.
CameraPath read_camera_path(const std::filesystem::path& path);

// The object form of every keyframe, numbers written so they read back bit for bit.
Json to_json(const CameraPath& path);
// Written atomically (temporary file, then rename): the viewer records paths while a movie job may
// be reading the previous version. Throws InputError (as parse_camera_path) for a path that would
// not read back, before anything is written.
void write_camera_path(const std::filesystem::path& path, const CameraPath& camera_path);

// The camera at `time` seconds, clamped to the keyframes' range. Throws std::invalid_argument if
// the interpolated camera is degenerate (parse_camera_path rules this out at every frame time).
Camera camera_at(const CameraPath& path, double time);

// Movie frame file names ("frames/%05d.png"): `pattern` holds exactly one printf-style integer
// conversion, %d with an optional 0 flag and width (%d, %5d, %05d), and no other % but %%.
// check_frame_pattern throws an InputError against `source` (the option that gave the pattern)
// saying what is wrong; frame_file_name expects a checked pattern.
void check_frame_pattern(std::string_view pattern, const InputSource& source);
std::string frame_file_name(std::string_view pattern, std::uint64_t frame);

}  // namespace nano::render
