#pragma once
// The viewer's two cameras over one Camera, free of any window system so they can be
// tested: orbit (rotate about the target, pan, dolly) and fly (move along the view, mouse look).
// Every step is relative to the distance it acts at — dolly is a factor per wheel step, pan moves
// the target by what the cursor covers at the target's depth, fly speed follows the distance to
// what is in front — so the same motions work 10 Å from an atom and 10 µm from a blood cell.
#include <cstdint>
#include <optional>

#include <glm/vec3.hpp>

#include "format/package.hpp"
#include "runtime/render/camera_spec.hpp"

namespace nano::viewer {

struct Bounds {
  glm::dvec3 lo{0.0}, hi{0.0};
  double radius() const;  // half the diagonal
  glm::dvec3 centre() const { return (lo + hi) * 0.5; }
};

// World box of every compartment instance's mesh (corners through the instance transform); a
// ±1000 Å box about the origin for a package without instances.
Bounds scene_bounds(const format::Package& package);

class CameraController {
public:
  enum class Mode { orbit, fly };

  CameraController(const Camera& start, double scene_radius);

  const Camera& camera() const { return camera_; }
  void set_camera(const Camera& camera);  // checked (throws std::invalid_argument)
  Mode mode() const { return mode_; }
  // Switching to orbit keeps the eye and orbits about what the view centre showed, when known.
  void set_mode(Mode mode);
  void toggle_mode() { set_mode(mode_ == Mode::orbit ? Mode::fly : Mode::orbit); }

  double distance() const;  // eye to target, Å
  // Depth (Å) of what the centre of the last frame showed; nullopt: background. Fly speed follows it.
  void set_focus_depth(std::optional<double> depth) { focus_depth_ = depth; }

  // Orbit: a drag across the whole viewport height turns the view by 180°. Keeps the distance to
  // the target; the elevation stops 1° short of the up hint so the camera never becomes degenerate.
  void orbit(double dx_pixels, double dy_pixels, double viewport_height);
  // Pan: eye and target move together so the point at the target's depth follows the cursor.
  void pan(double dx_pixels, double dy_pixels, double viewport_height);
  // Dolly: each wheel step (positive: towards the target) scales the distance by 0.85, between
  // 0.5 Å and 100 scene radii.
  void dolly(double wheel_steps);
  // Fly: mouse look turns eye direction about the up hint (yaw) and the right axis (pitch).
  void look(double dx_pixels, double dy_pixels, double viewport_height);
  // Fly: `axes` = (right, up, forward) in [-1, 1], for `seconds`; `fast` multiplies speed by 5.
  void fly(const glm::dvec3& axes, double seconds, bool fast);
  double fly_speed() const;  // Å per second

private:
  Camera camera_;
  double scene_radius_;
  Mode mode_ = Mode::orbit;
  std::optional<double> focus_depth_;
};

}  // namespace nano::viewer
