#include "runtime/viewer/camera_controller.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "shared/package_records.h"

namespace nano::viewer {
namespace {

constexpr double kMinDistance = 0.5;         // Å: about a third of an atom
constexpr double kPoleMargin = glm::radians(1.0);

glm::dvec3 rotate(const glm::dvec3& v, const glm::dvec3& axis, double angle) {
  return glm::angleAxis(angle, glm::normalize(axis)) * v;
}

}  // namespace

double Bounds::radius() const { return 0.5 * glm::length(hi - lo); }

Bounds scene_bounds(const format::Package& package) {
  const auto meshes = package.records<format::SectionKind::meshes>();
  const auto compartments = package.records<format::SectionKind::compartments>();
  const auto instances = package.records<format::SectionKind::compartment_instances>();
  Bounds b{glm::dvec3(INFINITY), glm::dvec3(-INFINITY)};
  for (const gpu::CompartmentInstance& instance : instances) {
    if (instance.compartment >= compartments.size()) continue;
    const std::uint32_t mesh = compartments[instance.compartment].mesh;
    if (mesh >= meshes.size()) continue;
    const glm::dvec3 lo(glm::vec3(meshes[mesh].aabb_min)), hi(glm::vec3(meshes[mesh].aabb_max));
    for (int corner = 0; corner < 8; ++corner) {
      const glm::dvec4 p(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z, 1.0);
      glm::dvec3 w;
      for (int r = 0; r < 3; ++r) w[r] = glm::dot(glm::dvec4(instance.transform[r]), p);
      b.lo = glm::min(b.lo, w);
      b.hi = glm::max(b.hi, w);
    }
  }
  if (!(b.lo.x <= b.hi.x)) return Bounds{glm::dvec3(-1000.0), glm::dvec3(1000.0)};
  return b;
}

CameraController::CameraController(const Camera& start, double scene_radius)
    : camera_(start), scene_radius_(std::max(scene_radius, 1.0)) {
  camera_.check();
}

void CameraController::set_camera(const Camera& camera) {
  camera.check();
  camera_ = camera;
}

void CameraController::set_mode(Mode mode) {
  if (mode == Mode::orbit && mode_ == Mode::fly && focus_depth_ && *focus_depth_ > kMinDistance) {
    const glm::dvec3 forward = glm::normalize(camera_.look_at - camera_.position);
    camera_.look_at = camera_.position + forward * *focus_depth_;
  }
  mode_ = mode;
}

double CameraController::distance() const { return glm::length(camera_.look_at - camera_.position); }

void CameraController::orbit(double dx, double dy, double viewport_height) {
  const double per_pixel = glm::pi<double>() / std::max(viewport_height, 1.0);
  const glm::dvec3 up = glm::normalize(camera_.up);
  glm::dvec3 offset = camera_.position - camera_.look_at;
  const double d = glm::length(offset);
  // Yaw about the up hint: dragging right moves the camera left around the target, so the scene
  // turns with the cursor.
  offset = rotate(offset, up, -dx * per_pixel);
  // Pitch about the camera's right axis, clamped away from the poles.
  const double elevation = std::acos(std::clamp(glm::dot(glm::normalize(offset), up), -1.0, 1.0));
  const double target = std::clamp(elevation - dy * per_pixel, kPoleMargin, glm::pi<double>() - kPoleMargin);
  const glm::dvec3 right = glm::cross(-offset, up);
  if (glm::length(right) > 0) offset = rotate(offset, right, target - elevation);
  // Renormalised so many small rotations never drift the distance.
  camera_.position = camera_.look_at + glm::normalize(offset) * d;
}

void CameraController::pan(double dx, double dy, double viewport_height) {
  const glm::dvec3 forward = glm::normalize(camera_.look_at - camera_.position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera_.up));
  const glm::dvec3 up = glm::cross(right, forward);
  // Å per pixel at the target's depth: the viewport spans 2·d·tan(fov/2) vertically there.
  const double scale = 2 * distance() * std::tan(glm::radians(camera_.fov_degrees) * 0.5) / std::max(viewport_height, 1.0);
  const glm::dvec3 move = (-dx * right + dy * up) * scale;
  camera_.position += move;
  camera_.look_at += move;
}

void CameraController::dolly(double wheel_steps) {
  const glm::dvec3 forward = glm::normalize(camera_.look_at - camera_.position);
  const double d = std::clamp(distance() * std::pow(0.85, wheel_steps), kMinDistance, 100 * scene_radius_);
  camera_.position = camera_.look_at - forward * d;
}

void CameraController::look(double dx, double dy, double viewport_height) {
  const double per_pixel = glm::radians(camera_.fov_degrees) / std::max(viewport_height, 1.0);
  const glm::dvec3 up = glm::normalize(camera_.up);
  const double d = distance();
  glm::dvec3 forward = glm::normalize(camera_.look_at - camera_.position);
  forward = rotate(forward, up, -dx * per_pixel);
  const double elevation = std::acos(std::clamp(glm::dot(forward, up), -1.0, 1.0));
  const double target = std::clamp(elevation + dy * per_pixel, kPoleMargin, glm::pi<double>() - kPoleMargin);
  const glm::dvec3 right = glm::cross(forward, up);
  if (glm::length(right) > 0) forward = rotate(forward, right, -(target - elevation));
  camera_.look_at = camera_.position + glm::normalize(forward) * d;
}

double CameraController::fly_speed() const {
  // Half the distance to what is in front per second: approaching a surface slows down on its own
  // and never passes it within a second; over the background the target's distance stands in.
  const double reach = focus_depth_ ? *focus_depth_ : distance();
  return 0.5 * std::clamp(reach, 2 * kMinDistance, 4 * scene_radius_);
}

void CameraController::fly(const glm::dvec3& axes, double seconds, bool fast) {
  if (axes == glm::dvec3(0.0) || seconds <= 0) return;
  const glm::dvec3 forward = glm::normalize(camera_.look_at - camera_.position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera_.up));
  const glm::dvec3 up = glm::cross(right, forward);
  const glm::dvec3 move = (axes.x * right + axes.y * up + axes.z * forward) * (fly_speed() * seconds * (fast ? 5.0 : 1.0));
  camera_.position += move;
  camera_.look_at += move;
}

}  // namespace nano::viewer
