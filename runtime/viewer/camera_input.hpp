#pragma once
// Mouse and keyboard (as Dear ImGui's IO sees them, so the panel gets first claim) to camera
// motions: orbit mode — left drag rotates, right or middle drag pans, wheel dollies; fly mode —
// W/A/S/D/Q/E move (Shift: ×5), left drag looks, wheel dollies the target. Tab toggles the mode.
// A left click without a drag is a pick; F12 or P asks for a screenshot; K adds the camera to the
// camera path as a keyframe and L plays (or stops) the path.
#include <optional>
#include <vector>
#include <utility>

#include "runtime/viewer/camera_controller.hpp"
#include "runtime/viewer/window.hpp"

namespace nano::viewer {

struct InputResult {
  bool camera_moved = false;    // the camera changed this frame
  bool dragging = false;        // a button is held over the scene (more motion is likely)
  std::optional<std::pair<double, double>> click;  // window coordinates (ImGui's, logical pixels)
  bool screenshot = false;
  bool add_keyframe = false;    // K
  bool toggle_path = false;     // L
  bool toggle_ambient_occlusion = false;  // O
  std::vector<int> keys;        // every key pressed since the last call (GLFW codes), in order
};

// Call between Overlay::begin_frame and end_frame. `seconds`: time since the previous call.
InputResult handle_camera_input(Window& window, CameraController& camera, double seconds);

}  // namespace nano::viewer
