#pragma once
// The GLFW window: initialisation with a clear message when no display is available, the instance
// extensions its Vulkan surface needs, and the surface itself. One window per process.
#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

struct GLFWwindow;

namespace nano::viewer {

class Window {
public:
  // Throws std::runtime_error naming GLFW's reason when there is no display or no Vulkan loader.
  Window(std::uint32_t width, std::uint32_t height, const std::string& title);
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;
  ~Window();

  GLFWwindow* handle() const { return window_; }
  // VK_KHR_surface and the platform's surface extension (xcb or xlib under X11).
  std::vector<std::string> required_instance_extensions() const;
  VkSurfaceKHR create_surface(VkInstance instance) const;

  bool should_close() const;
  void request_close();
  // Pixels the swapchain must cover; (0, 0) while minimised.
  std::pair<std::uint32_t, std::uint32_t> framebuffer_size() const;
  void resize(std::uint32_t width, std::uint32_t height);
  void set_title(const std::string& title);

  // Keys pressed since the last call, in order. Kept here because a frame can take seconds: a key
  // tapped during it is pressed and released within one poll, and Dear ImGui 1.86, which only
  // sees the state at each new frame, would miss it.
  std::vector<int> take_key_presses();
  bool key_down(int key) const;

  // When each key of the last take_key_presses() reached the viewer, by the viewer's clock: its
  // callback ran at `received`, and it cannot have waited in the event queue since before
  // `queued_after`, the end of the poll before the one that delivered it (the viewer's own bound on
  // how long input waited for it; NANO_VIEW_INPUT_LOG reports it).
  struct KeyTimes {
    std::chrono::steady_clock::time_point queued_after, received;
  };
  const std::vector<KeyTimes>& last_key_times() const { return taken_times_; }

  void poll_events();
  // Sleeps until an event arrives or `seconds` pass (a resting viewer uses no CPU).
  void wait_events(double seconds);

private:
  static void on_key(GLFWwindow* window, int key, int scancode, int action, int mods);

  GLFWwindow* window_ = nullptr;
  std::vector<int> pressed_;
  std::vector<KeyTimes> pressed_times_, taken_times_;   // parallel to pressed_ / the last presses taken
  std::chrono::steady_clock::time_point polled_{std::chrono::steady_clock::now()};  // the last poll's end
};

}  // namespace nano::viewer
