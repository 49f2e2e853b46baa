#include "runtime/viewer/camera_input.hpp"

#include <algorithm>
#include <vector>

#include <GLFW/glfw3.h>
#include <imgui.h>

namespace nano::viewer {

InputResult handle_camera_input(Window& window, CameraController& camera, double seconds) {
  InputResult r;
  const ImGuiIO& io = ImGui::GetIO();
  const double height = io.DisplaySize.y;
  const bool fly = camera.mode() == CameraController::Mode::fly;

  if (!io.WantCaptureMouse) {
    const ImVec2 delta = io.MouseDelta;
    const bool moved = delta.x != 0 || delta.y != 0;
    if (ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
      r.dragging = true;
      // Below the click threshold the press may still become a pick; do not turn the view yet.
      if (moved && ImGui::IsMouseDragging(ImGuiMouseButton_Left)) {
        if (fly) camera.look(delta.x, delta.y, height);
        else camera.orbit(delta.x, delta.y, height);
        r.camera_moved = true;
      }
    }
    for (ImGuiMouseButton button : {ImGuiMouseButton_Right, ImGuiMouseButton_Middle})
      if (ImGui::IsMouseDown(button)) {
        r.dragging = true;
        if (moved) {
          camera.pan(delta.x, delta.y, height);
          r.camera_moved = true;
        }
      }
    if (io.MouseWheel != 0) {
      camera.dolly(io.MouseWheel);
      r.camera_moved = true;
    }
    // A release that never travelled beyond ImGui's drag threshold is a click.
    if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) &&
        io.MouseDragMaxDistanceSqr[ImGuiMouseButton_Left] < io.MouseDragThreshold * io.MouseDragThreshold)
      r.click = std::pair(double(io.MousePos.x), double(io.MousePos.y));
  }

  const std::vector<int> presses = window.take_key_presses();
  r.keys = presses;
  if (!io.WantCaptureKeyboard) {
    const auto pressed = [&](int key) { return std::find(presses.begin(), presses.end(), key) != presses.end(); };
    if (pressed(GLFW_KEY_TAB)) camera.toggle_mode();
    if (pressed(GLFW_KEY_F12) || pressed(GLFW_KEY_P)) r.screenshot = true;
    r.add_keyframe = pressed(GLFW_KEY_K);
    r.toggle_path = pressed(GLFW_KEY_L);
    r.toggle_ambient_occlusion = pressed(GLFW_KEY_O);
    if (camera.mode() == CameraController::Mode::fly) {
      // Held, or tapped during the last frame (then it moves for that frame's time, capped below).
      const auto down = [&](int key) { return window.key_down(key) || pressed(key) ? 1.0 : 0.0; };
      const glm::dvec3 axes(down(GLFW_KEY_D) - down(GLFW_KEY_A), down(GLFW_KEY_E) - down(GLFW_KEY_Q),
                            down(GLFW_KEY_W) - down(GLFW_KEY_S));
      if (axes != glm::dvec3(0.0)) {
        // The frame before may have taken seconds (a full-resolution frame); cap the step so one
        // key press never jumps across the scene.
        const bool fast = window.key_down(GLFW_KEY_LEFT_SHIFT) || window.key_down(GLFW_KEY_RIGHT_SHIFT);
        camera.fly(axes, std::min(seconds, 0.25), fast);
        r.camera_moved = true;
        r.dragging = true;
      }
    }
  }
  return r;
}

}  // namespace nano::viewer
