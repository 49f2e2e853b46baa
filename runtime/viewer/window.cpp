#include "runtime/viewer/window.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "runtime/vk/error.hpp"

namespace nano::viewer {
namespace {

std::string last_glfw_error() {
  const char* description = nullptr;
  const int code = glfwGetError(&description);
  if (code == GLFW_NO_ERROR) return "no reason given";
  return description ? description : "error " + std::to_string(code);
}

}  // namespace

Window::Window(std::uint32_t width, std::uint32_t height, const std::string& title) {
  if (!glfwInit())
    throw std::runtime_error("cannot open a window: " + last_glfw_error() +
                             " (is DISPLAY set? without a display run under xvfb-run)");
  if (!glfwVulkanSupported()) {
    const std::string reason = last_glfw_error();
    glfwTerminate();
    throw std::runtime_error("cannot open a window: GLFW finds no Vulkan loader (" + reason + ")");
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);  // Vulkan presents; no GL context
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
  if (window_ == nullptr) {
    const std::string reason = last_glfw_error();
    glfwTerminate();
    throw std::runtime_error("cannot create a " + std::to_string(width) + "x" + std::to_string(height) +
                             " window: " + reason);
  }
  // Installed before Dear ImGui's backend, which chains to callbacks it finds in place.
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, &Window::on_key);
}

void Window::on_key(GLFWwindow* window, int key, int, int action, int) {
  if (action != GLFW_PRESS) return;
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(window));
  if (self && self->pressed_.size() < 256) {
    self->pressed_.push_back(key);
    self->pressed_times_.push_back({self->polled_, std::chrono::steady_clock::now()});
  }
}

std::vector<int> Window::take_key_presses() {
  taken_times_ = std::exchange(pressed_times_, {});
  return std::exchange(pressed_, {});
}
bool Window::key_down(int key) const { return glfwGetKey(window_, key) == GLFW_PRESS; }

Window::~Window() {
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

std::vector<std::string> Window::required_instance_extensions() const {
  std::uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  if (names == nullptr)
    throw std::runtime_error("GLFW cannot present with Vulkan on this window system: " + last_glfw_error());
  return std::vector<std::string>(names, names + count);
}

VkSurfaceKHR Window::create_surface(VkInstance instance) const {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  vk::check(glfwCreateWindowSurface(instance, window_, nullptr, &surface), "glfwCreateWindowSurface");
  return surface;
}

bool Window::should_close() const { return glfwWindowShouldClose(window_); }
void Window::request_close() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }

std::pair<std::uint32_t, std::uint32_t> Window::framebuffer_size() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  if (glfwGetWindowAttrib(window_, GLFW_ICONIFIED)) return {0, 0};
  return {std::uint32_t(std::max(w, 0)), std::uint32_t(std::max(h, 0))};
}

void Window::resize(std::uint32_t width, std::uint32_t height) { glfwSetWindowSize(window_, int(width), int(height)); }
void Window::set_title(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }
void Window::poll_events() {
  glfwPollEvents();
  polled_ = std::chrono::steady_clock::now();
}
void Window::wait_events(double seconds) {
  glfwWaitEventsTimeout(seconds);
  polled_ = std::chrono::steady_clock::now();
}

}  // namespace nano::viewer
