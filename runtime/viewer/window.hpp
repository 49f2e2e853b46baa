#pragma once
// The GLFW window: initialisation with a clear message when no display is available, the instance
// extensions its Vulkan surface needs, and the surface itself. One window per process.
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

  void poll_events();
  // Sleeps until an event arrives or `seconds` pass (a resting viewer uses no CPU).
  void wait_events(double seconds);

private:
  static void on_key(GLFWwindow* window, int key, int scancode, int action, int mods);

  GLFWwindow* window_ = nullptr;
  std::vector<int> pressed_;
};

}  // namespace nano::viewer
