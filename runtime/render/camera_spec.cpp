#include "runtime/render/camera_spec.hpp"

#include <charconv>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace nano::render {
namespace {

glm::dvec3 parse_vector(std::string_view key, std::string_view value) {
  glm::dvec3 v;
  std::string s(value);
  char tail = 0;
  if (std::sscanf(s.c_str(), "%lf,%lf,%lf%c", &v.x, &v.y, &v.z, &tail) != 3 || !std::isfinite(v.x) ||
      !std::isfinite(v.y) || !std::isfinite(v.z))
    throw std::invalid_argument("camera: '" + std::string(key) + "=" + s + "' is not three finite numbers x,y,z");
  return v;
}

}  // namespace

void CameraSpec::check() const {
  const glm::dvec3 f = at - eye;
  if (!(glm::length(f) > 0)) throw std::invalid_argument("camera: pos and at are the same point");
  if (!(glm::length(glm::cross(f / glm::length(f), up)) > 1e-9 * glm::length(up)))
    throw std::invalid_argument("camera: up is zero or parallel to the viewing direction");
  if (!(fov_degrees > 0 && fov_degrees < 180)) throw std::invalid_argument("camera: fov must lie in (0, 180) degrees");
}

gpu::Camera CameraSpec::to_gpu(std::uint32_t width, std::uint32_t height) const {
  check();
  if (width == 0 || height == 0) throw std::invalid_argument("camera: image size must be positive");
  return gpu::camera_look_at(glm::vec3(eye), glm::vec3(at), glm::vec3(up), float(fov_degrees), width, height);
}

std::string CameraSpec::to_string() const {
  // Shortest text that reads back to the same doubles: a printed camera renders the same frame.
  const auto number = [](double v) {
    char buffer[32];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
    return std::string(buffer, end);
  };
  const auto triple = [&](const glm::dvec3& v) { return number(v.x) + "," + number(v.y) + "," + number(v.z); };
  return "pos=" + triple(eye) + ";at=" + triple(at) + ";up=" + triple(up) + ";fov=" + number(fov_degrees);
}

float depth_cue_for(const CameraSpec& camera) { return float(4 * glm::length(camera.at - camera.eye)); }

CameraSpec parse_camera(std::string_view text, const CameraSpec& base) {
  CameraSpec c = base;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(';', start), text.size());
    const std::string_view part = text.substr(start, end - start);
    start = end + 1;
    if (part.empty()) continue;
    const std::size_t eq = part.find('=');
    if (eq == std::string_view::npos) throw std::invalid_argument("camera: '" + std::string(part) + "' has no '='");
    const std::string_view key = part.substr(0, eq), value = part.substr(eq + 1);
    if (key == "pos") c.eye = parse_vector(key, value);
    else if (key == "at") c.at = parse_vector(key, value);
    else if (key == "up") c.up = parse_vector(key, value);
    else if (key == "fov") {
      std::string s(value);
      char tail = 0;
      if (std::sscanf(s.c_str(), "%lf%c", &c.fov_degrees, &tail) != 1)
        throw std::invalid_argument("camera: 'fov=" + s + "' is not a number of degrees");
    } else {
      throw std::invalid_argument("camera: unknown key '" + std::string(key) + "' (pos, at, up, fov)");
    }
  }
  c.check();
  return c;
}

CameraSpec package_camera(const format::Package& package) {
  CameraSpec c;
  const auto scene = package.records<format::SectionKind::scene>();
  if (scene.empty()) return c;
  const gpu::SceneSettings& s = scene[0];
  c.eye = glm::dvec3(glm::vec3(s.camera_eye));
  c.at = glm::dvec3(glm::vec3(s.camera_target));
  c.up = glm::dvec3(glm::vec3(s.camera_up));
  c.fov_degrees = glm::degrees(double(s.camera_eye.w));
  c.check();
  return c;
}

}  // namespace nano::render
