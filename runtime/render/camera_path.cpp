#include "runtime/render/camera_path.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "common/atomic_file.hpp"
#include "common/error.hpp"

namespace nano::render {
namespace {

constexpr const char* kFormat = "nanouniverse-camera-path";
constexpr double kMaxFps = 1000;
// Parsing evaluates the camera at every frame time; this bounds that work (≈ 92 hours at 30 fps).
constexpr std::uint64_t kMaxFrames = 10'000'000;

double number(const nlohmann::json& j, const std::string& file, const std::string& where) {
  if (!j.is_number() || !std::isfinite(j.get<double>())) throw InputError(file, where, "expected a finite number");
  return j.get<double>();
}

glm::dvec3 vector3(const nlohmann::json& j, const std::string& file, const std::string& where) {
  if (!j.is_array() || j.size() != 3) throw InputError(file, where, "expected an array of three numbers [x, y, z]");
  return {number(j[0], file, where + "[0]"), number(j[1], file, where + "[1]"), number(j[2], file, where + "[2]")};
}

// Hermite tangent of eye or target at key i, per second: Catmull–Rom's central difference over
// the neighbours' time span (so unequal key spacing keeps the speed continuous), one-sided at the ends.
glm::dvec3 tangent(const std::vector<CameraKeyframe>& keys, std::size_t i, glm::dvec3 Camera::*member) {
  const std::size_t lo = i == 0 ? 0 : i - 1, hi = std::min(i + 1, keys.size() - 1);
  if (lo == hi) return glm::dvec3(0.0);
  return (keys[hi].camera.*member - keys[lo].camera.*member) / (keys[hi].time - keys[lo].time);
}

}  // namespace

std::uint64_t CameraPath::frame_count() const {
  // The small slack keeps a duration such as 0.7 s at 30 fps (0.7·30 = 20.999…96 in double) at 22 frames.
  return std::uint64_t(std::floor(duration() * fps + 1e-9)) + 1;
}

Camera camera_at(const CameraPath& path, double time) {
  const auto& keys = path.keyframes;
  if (keys.empty()) throw std::invalid_argument("camera path: no keyframes");
  if (!(time > keys.front().time)) return keys.front().camera;  // NaN clamps to the start too
  if (time >= keys.back().time) return keys.back().camera;
  const std::size_t i =
      std::size_t(std::upper_bound(keys.begin(), keys.end(), time, [](double t, const CameraKeyframe& k) { return t < k.time; }) -
                  keys.begin()) - 1;
  const CameraKeyframe &a = keys[i], &b = keys[i + 1];
  if (time == a.time) return a.camera;
  const double dt = b.time - a.time, s = (time - a.time) / dt;
  const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s), h01 = s * s * (3 - 2 * s),
               h11 = s * s * (s - 1);
  const auto hermite = [&](glm::dvec3 Camera::*member) {
    return h00 * a.camera.*member + h10 * dt * tangent(keys, i, member) + h01 * b.camera.*member +
           h11 * dt * tangent(keys, i + 1, member);
  };
  Camera c;
  c.eye = hermite(&Camera::eye);
  c.at = hermite(&Camera::at);
  c.up = glm::normalize((1 - s) * glm::normalize(a.camera.up) + s * glm::normalize(b.camera.up));
  c.fov_degrees = (1 - s) * a.camera.fov_degrees + s * b.camera.fov_degrees;
  c.check();
  return c;
}

CameraPath parse_camera_path(const nlohmann::json& json, const std::string& file) {
  if (!json.is_object()) throw InputError(file, "", "a camera path is a JSON object");
  for (const auto& [key, value] : json.items())
    if (key != "format" && key != "version" && key != "fps" && key != "keyframes")
      throw InputError(file, key, "unknown key (format, version, fps, keyframes)");
  if (!json.contains("format") || json["format"] != kFormat)
    throw InputError(file, "format", std::string("expected \"") + kFormat + "\"");
  if (!json.contains("version") || json["version"] != 1) throw InputError(file, "version", "expected 1");
  CameraPath path;
  if (json.contains("fps")) path.fps = number(json["fps"], file, "fps");
  if (!(path.fps > 0 && path.fps <= kMaxFps)) throw InputError(file, "fps", "frames per second must lie in (0, 1000]");
  if (!json.contains("keyframes") || !json["keyframes"].is_array() || json["keyframes"].empty())
    throw InputError(file, "keyframes", "expected a non-empty array of keyframes");

  Camera previous;
  for (std::size_t i = 0; i < json["keyframes"].size(); ++i) {
    const nlohmann::json& k = json["keyframes"][i];
    const std::string where = "keyframes[" + std::to_string(i) + "]";
    if (!k.is_object()) throw InputError(file, where, "expected an object");
    for (const auto& [key, value] : k.items())
      if (key != "time" && key != "camera" && key != "position" && key != "look_at" && key != "up" && key != "fov_degrees")
        throw InputError(file, where + "." + key, "unknown key (time, camera, or position, look_at, up, fov_degrees)");
    CameraKeyframe key;
    if (!k.contains("time")) throw InputError(file, where + ".time", "missing");
    key.time = number(k["time"], file, where + ".time");
    if (key.time < 0) throw InputError(file, where + ".time", "must be ≥ 0 s");
    if (!path.keyframes.empty() && !(key.time > path.keyframes.back().time))
      throw InputError(file, where + ".time", "times must increase strictly");
    key.camera = previous;
    try {
      if (k.contains("camera")) {
        for (const char* other : {"position", "look_at", "up", "fov_degrees"})
          if (k.contains(other))
            throw InputError(file, where + "." + other, "give either \"camera\" or position/look_at/up/fov_degrees, not both");
        if (!k["camera"].is_string()) throw InputError(file, where + ".camera", "expected a string pos=..;at=..;up=..;fov=..");
        key.camera = parse_camera(k["camera"].get<std::string>(), previous);
      } else {
        if (k.contains("position")) key.camera.eye = vector3(k["position"], file, where + ".position");
        if (k.contains("look_at")) key.camera.at = vector3(k["look_at"], file, where + ".look_at");
        if (k.contains("up")) key.camera.up = vector3(k["up"], file, where + ".up");
        if (k.contains("fov_degrees")) key.camera.fov_degrees = number(k["fov_degrees"], file, where + ".fov_degrees");
        key.camera.check();
      }
    } catch (const std::invalid_argument& e) {
      throw InputError(file, where, e.what());
    }
    // Normalised lerp has no answer halfway between opposite up vectors.
    if (!path.keyframes.empty() &&
        glm::dot(glm::normalize(key.camera.up), glm::normalize(path.keyframes.back().camera.up)) < -1 + 1e-9)
      throw InputError(file, where + ".up", "turns by 180° from the previous keyframe's up; add a keyframe between them");
    previous = key.camera;
    path.keyframes.push_back(key);
  }
  if (double(path.duration()) * path.fps >= double(kMaxFrames))
    throw InputError(file, "keyframes", "more than " + std::to_string(kMaxFrames) + " frames");
  // Keyframes can be fine while the spline between them passes the eye through the target.
  for (std::uint64_t f = 0; f < path.frame_count(); ++f) {
    try {
      camera_at(path, path.frame_time(f));
    } catch (const std::invalid_argument& e) {
      throw InputError(file, "keyframes", "frame " + std::to_string(f) + " (time " + std::to_string(path.frame_time(f)) +
                                              " s) has a degenerate camera: " + e.what());
    }
  }
  return path;
}

CameraPath read_camera_path(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(name, "", "cannot open the camera path for reading");
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(name, "", std::string("not valid JSON: ") + e.what());
  }
  return parse_camera_path(json, name);
}

nlohmann::json to_json(const CameraPath& path) {
  nlohmann::json keys = nlohmann::json::array();
  for (const CameraKeyframe& k : path.keyframes)
    keys.push_back({{"time", k.time},
                    {"position", {k.camera.eye.x, k.camera.eye.y, k.camera.eye.z}},
                    {"look_at", {k.camera.at.x, k.camera.at.y, k.camera.at.z}},
                    {"up", {k.camera.up.x, k.camera.up.y, k.camera.up.z}},
                    {"fov_degrees", k.camera.fov_degrees}});
  return {{"format", kFormat}, {"version", 1}, {"fps", path.fps}, {"keyframes", keys}};
}

void write_camera_path(const std::filesystem::path& path, const CameraPath& camera_path) {
  const nlohmann::json json = to_json(camera_path);
  parse_camera_path(json, path.string());  // never write a file that would not read back
  const std::string text = json.dump(2) + "\n";
  write_file_atomically(path, std::as_bytes(std::span(text.data(), text.size())));
}

namespace {

// Calls `literal(text)` for the text between conversions and `conversion(zero_pad, width)` for
// each %d; throws on anything else, so checking and formatting cannot disagree.
template <class Literal, class Conversion>
void walk_pattern(std::string_view pattern, Literal literal, Conversion conversion) {
  int conversions = 0;
  for (std::size_t i = 0; i < pattern.size();) {
    const std::size_t percent = pattern.find('%', i);
    literal(pattern.substr(i, percent == std::string_view::npos ? std::string_view::npos : percent - i));
    if (percent == std::string_view::npos) break;
    std::size_t j = percent + 1;
    if (j < pattern.size() && pattern[j] == '%') {
      literal("%");
      i = j + 1;
      continue;
    }
    const bool zero = j < pattern.size() && pattern[j] == '0';
    j += zero;
    std::size_t width = 0;
    while (j < pattern.size() && pattern[j] >= '0' && pattern[j] <= '9' && width < 1000) width = 10 * width + (pattern[j++] - '0');
    if (j >= pattern.size() || pattern[j] != 'd' || width > 20)
      throw std::invalid_argument("'" + std::string(pattern) + "': the only conversion allowed is one %d for the frame number (" +
                                  "optionally %05d or %5d, width ≤ 20); write a literal % as %%");
    conversion(zero, width);
    ++conversions;
    i = j + 1;
  }
  if (conversions != 1)
    throw std::invalid_argument("'" + std::string(pattern) + "' must hold exactly one %d for the frame number (it holds " +
                                std::to_string(conversions) + ")");
}

}  // namespace

void check_frame_pattern(std::string_view pattern) {
  walk_pattern(pattern, [](std::string_view) {}, [](bool, std::size_t) {});
}

std::string frame_file_name(std::string_view pattern, std::uint64_t frame) {
  std::string out;
  walk_pattern(pattern, [&](std::string_view text) { out += text; },
               [&](bool zero, std::size_t width) {
                 const std::string digits = std::to_string(frame);
                 if (digits.size() < width) out.append(width - digits.size(), zero ? '0' : ' ');
                 out += digits;
               });
  return out;
}

}  // namespace nano::render
