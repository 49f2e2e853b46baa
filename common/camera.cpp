#include "common/camera.hpp"

#include <charconv>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace nano {

std::string Camera::problem() const {
  const glm::dvec3 f = look_at - position;
  if (!(glm::length(f) > 0)) return "camera: position and look_at are the same point";
  if (!(glm::length(glm::cross(f / glm::length(f), up)) > 1e-9 * glm::length(up)))
    return "camera: up is zero or parallel to the viewing direction";
  if (!(fov_degrees > 0 && fov_degrees < 180)) return "camera: fov_degrees must lie in (0, 180)";
  return {};
}

void Camera::check() const {
  if (const std::string wrong = problem(); !wrong.empty()) throw std::invalid_argument(wrong);
}

gpu::Camera Camera::to_gpu(std::uint32_t width, std::uint32_t height) const {
  check();
  if (width == 0 || height == 0) throw std::invalid_argument("camera: image size must be positive");
  return gpu::camera_look_at(glm::vec3(position), glm::vec3(look_at), glm::vec3(up), float(fov_degrees), width, height);
}

std::string Camera::to_string() const {
  // Shortest text that reads back to the same doubles: a printed camera renders the same frame.
  const auto number = [](double v) {
    char buffer[32];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
    return std::string(buffer, end);
  };
  const auto triple = [&](const glm::dvec3& v) { return number(v.x) + "," + number(v.y) + "," + number(v.z); };
  return "position=" + triple(position) + ";look_at=" + triple(look_at) + ";up=" + triple(up) + ";fov_degrees=" + number(fov_degrees);
}

Camera camera_from_scene(const gpu::SceneSettings& scene) {
  Camera c;
  c.position = glm::dvec3(glm::vec3(scene.camera_position));
  c.look_at = glm::dvec3(glm::vec3(scene.camera_look_at));
  c.up = glm::dvec3(glm::vec3(scene.camera_up));
  c.fov_degrees = glm::degrees(double(scene.camera_position.w));
  return c;
}

void store_camera(gpu::SceneSettings& scene, const Camera& camera) {
  scene.camera_position = glm::vec4(glm::vec3(camera.position), static_cast<float>(glm::radians(camera.fov_degrees)));
  scene.camera_look_at = glm::vec4(glm::vec3(camera.look_at), 0.f);
  scene.camera_up = glm::vec4(glm::vec3(camera.up), 0.f);
}

}  // namespace nano
