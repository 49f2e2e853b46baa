#include "runtime/render/camera_path.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/json_cursor.hpp"

namespace nano::render {
namespace {

constexpr const char* kFormat = "nanouniverse-camera-path";
constexpr double kMaxFps = 1000;
// Parsing evaluates the camera at every frame time; this bounds that work (≈ 92 hours at 30 fps).
constexpr std::uint64_t kMaxFrames = 10'000'000;

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

namespace {

// camera_at without its check: the reader reports a degenerate frame against the file instead.
Camera interpolated_camera(const CameraPath& path, double time) {
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
  c.position = hermite(&Camera::position);
  c.look_at = hermite(&Camera::look_at);
  c.up = glm::normalize((1 - s) * glm::normalize(a.camera.up) + s * glm::normalize(b.camera.up));
  c.fov_degrees = (1 - s) * a.camera.fov_degrees + s * b.camera.fov_degrees;
  return c;
}

}  // namespace

Camera camera_at(const CameraPath& path, double time) {
  const Camera c = interpolated_camera(path, time);
  c.check();
  return c;
}

CameraPath parse_camera_path(const Json& json, const std::string& file) {
  const JsonCursor root(json, file);
  root.only_keys({"format", "version", "fps", "keyframes"});
  const JsonCursor format = root.required("format");
  if (format.string() != kFormat) format.fail(std::string("expected \"") + kFormat + "\", got " + format.shown());
  const JsonCursor version = root.required("version");
  if (version.json() != 1) version.fail("expected 1, got " + version.shown());
  CameraPath path;
  if (const auto fps = root.optional("fps")) {
    path.fps = fps->number();
    if (!(path.fps > 0 && path.fps <= kMaxFps)) fps->fail("frames per second must lie in (0, 1000], got " + fps->shown());
  }
  const JsonCursor keyframes = root.required("keyframes");

  Camera previous;
  for (const JsonCursor& k : keyframes.elements(1)) {
    k.only_keys({"time", "camera", "position", "look_at", "up", "fov_degrees"});
    CameraKeyframe key;
    const JsonCursor time = k.required("time");
    key.time = time.number_at_least(0);
    if (!path.keyframes.empty() && !(key.time > path.keyframes.back().time)) time.fail("times must increase strictly");
    key.camera = previous;
    if (const auto spec = k.optional("camera")) {
      for (const char* other : {"position", "look_at", "up", "fov_degrees"})
        if (k.has(other))
          k.required(other).fail("give either \"camera\" or position/look_at/up/fov_degrees, not both");
      key.camera = parse_camera(spec->string(), previous, spec->source());
    } else {
      if (const auto position = k.optional("position")) key.camera.position = position->vec3();
      if (const auto look_at = k.optional("look_at")) key.camera.look_at = look_at->vec3();
      if (const auto up = k.optional("up")) key.camera.up = up->vec3();
      if (const auto fov = k.optional("fov_degrees")) key.camera.fov_degrees = fov->number_strictly_between(0, 180);
      if (const std::string wrong = key.camera.problem(); !wrong.empty()) k.fail(wrong);
    }
    // Normalised lerp has no answer halfway between opposite up vectors.
    if (!path.keyframes.empty() &&
        glm::dot(glm::normalize(key.camera.up), glm::normalize(path.keyframes.back().camera.up)) < -1 + 1e-9)
      (k.has("up") ? k.required("up") : k)
          .fail("turns by 180° from the previous keyframe's up; add a keyframe between them");
    previous = key.camera;
    path.keyframes.push_back(key);
  }
  if (double(path.duration()) * path.fps >= double(kMaxFrames))
    keyframes.fail("more than " + std::to_string(kMaxFrames) + " frames");
  // Keyframes can be fine while the spline between them passes the eye through the target.
  for (std::uint64_t f = 0; f < path.frame_count(); ++f)
    if (const std::string wrong = interpolated_camera(path, path.frame_time(f)).problem(); !wrong.empty())
      keyframes.fail("frame " + std::to_string(f) + " (time " + std::to_string(path.frame_time(f)) + " s) has a degenerate camera: " + wrong);
  return path;
}

CameraPath read_camera_path(const std::filesystem::path& path) { return parse_camera_path(read_json_file(path), path.string()); }

Json to_json(const CameraPath& path) {
  Json keys = Json::array();
  for (const CameraKeyframe& k : path.keyframes)
    keys.push_back({{"time", k.time},
                    {"position", {k.camera.position.x, k.camera.position.y, k.camera.position.z}},
                    {"look_at", {k.camera.look_at.x, k.camera.look_at.y, k.camera.look_at.z}},
                    {"up", {k.camera.up.x, k.camera.up.y, k.camera.up.z}},
                    {"fov_degrees", k.camera.fov_degrees}});
  return {{"format", kFormat}, {"version", 1}, {"fps", path.fps}, {"keyframes", keys}};
}

void write_camera_path(const std::filesystem::path& path, const CameraPath& camera_path) {
  const std::string text = to_json(camera_path).dump(2) + "\n";
  parse_camera_path(parse_json_text(text, path.string()), path.string());  // never write a file that would not read back
  write_file_atomically(path, std::as_bytes(std::span(text.data(), text.size())));
}

namespace {

// Calls `literal(text)` for the text between conversions and `conversion(zero_pad, width)` for
// each %d, so checking and formatting cannot disagree; returns what is wrong with the pattern, or "".
template <class Literal, class Conversion>
std::string walk_pattern(std::string_view pattern, Literal literal, Conversion conversion) {
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
      return "'" + std::string(pattern) + "': the only conversion allowed is one %d for the frame number (" +
             "optionally %05d or %5d, width ≤ 20); write a literal % as %%";
    conversion(zero, width);
    ++conversions;
    i = j + 1;
  }
  if (conversions != 1)
    return "'" + std::string(pattern) + "' must hold exactly one %d for the frame number (it holds " + std::to_string(conversions) + ")";
  return {};
}

}  // namespace

void check_frame_pattern(std::string_view pattern, const InputSource& source) {
  if (const std::string wrong = walk_pattern(pattern, [](std::string_view) {}, [](bool, std::size_t) {}); !wrong.empty())
    source.fail(wrong);
}

std::string frame_file_name(std::string_view pattern, std::uint64_t frame) {
  std::string out;
  const std::string wrong = walk_pattern(pattern, [&](std::string_view text) { out += text; },
                                         [&](bool zero, std::size_t width) {
                                           const std::string digits = std::to_string(frame);
                                           if (digits.size() < width) out.append(width - digits.size(), zero ? '0' : ' ');
                                           out += digits;
                                         });
  if (!wrong.empty()) throw std::logic_error("frame_file_name before check_frame_pattern: " + wrong);
  return out;
}

}  // namespace nano::render
