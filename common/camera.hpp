#pragma once
// The one camera of Nanouniverse, from the scene file to the shader: position, look_at, up hint and
// vertical field of view in degrees. The baker reads it from scene.json and stores it in the
// package's scene record, render/verify/bench/the viewer take it from there or from --camera, and
// to_gpu makes the shader's record (shaders/shared/camera.h). The scene record keeps the field of
// view in radians: store_camera and camera_from_scene are the only conversions.
#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include "shared/camera.h"
#include "shared/package_records.h"

namespace nano {

// The vertical field of view of a camera that names none: scene.json's documented default
// (docs/scene.md), and also what the baker frames a scene without a camera with, what a camera
// path's first keyframe starts from and what --camera keys fill in when no scene camera is known.
inline constexpr double kDefaultFovDegrees = 45;

struct Camera {
  glm::dvec3 position{0.0, 0.0, 1000.0};
  glm::dvec3 look_at{0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fov_degrees = kDefaultFovDegrees;  // vertical

  // What makes this no camera, or "" when position ≠ look_at, up is not parallel to
  // look_at − position and 0 < fov < 180. Parsers report it against their InputSource.
  std::string problem() const;
  // For cameras that were checked on the way in: throws std::invalid_argument (a broken invariant)
  // with problem().
  void check() const;
  // The shader's camera for an image of width × height pixels (checks first).
  gpu::Camera to_gpu(std::uint32_t width, std::uint32_t height) const;
  // "position=x,y,z;look_at=x,y,z;up=x,y,z;fov_degrees=DEG" (the --camera form) with the shortest
  // numbers that read back to the same doubles.
  std::string to_string() const;
  bool operator==(const Camera&) const = default;
};

// The package's scene record and the camera (field of view: radians there, degrees here).
Camera camera_from_scene(const gpu::SceneSettings& scene);
void store_camera(gpu::SceneSettings& scene, const Camera& camera);

}  // namespace nano
