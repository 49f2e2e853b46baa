#pragma once
// The camera of `render`, `verify` and the viewer: eye, target, up hint and vertical field of view,
// parsed from "pos=x,y,z;at=x,y,z;up=x,y,z;fov=DEG" or taken from the package's scene record.
#include <cstdint>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "format/package.hpp"
#include "shared/camera.h"

namespace nano::render {

struct CameraSpec {
  glm::dvec3 eye{0.0, 0.0, 1000.0};
  glm::dvec3 at{0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fov_degrees = 40;

  // Throws std::invalid_argument unless eye ≠ at, up is not parallel to at − eye and 0 < fov < 180.
  void check() const;
  gpu::Camera to_gpu(std::uint32_t width, std::uint32_t height) const;
  std::string to_string() const;  // in the syntax parse_camera reads
};

// The depth cue `render`, `bench` and the viewer shade with: colour fades over four times the
// distance to the target (RenderSettings::depth_cue). One rule, so their frames stay identical.
float depth_cue_for(const CameraSpec& camera);

// Keys may come in any order and any may be left out (they keep `base`'s value). Throws
// std::invalid_argument naming the part that does not parse.
CameraSpec parse_camera(std::string_view text, const CameraSpec& base = {});

// The package's default camera (section scene), or a view of everything when it has none.
CameraSpec package_camera(const format::Package& package);

}  // namespace nano::render
