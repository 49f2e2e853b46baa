#pragma once
// The Vulkan instance, optionally with the Khronos validation layer and a debug messenger that
// prints and counts every warning and error, so tests can fail on any validation message.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace nano::vk {

struct InstanceOptions {
  // Enables VK_LAYER_KHRONOS_validation + VK_EXT_debug_utils; construction throws if the layer is
  // not installed, because a test that asked for validation must not silently run without it.
  bool validation = false;
  std::string application_name = "nanouniverse";
  // Extra instance extensions, e.g. the surface extensions a window system needs (GLFW names them);
  // the headless commands leave this empty.
  std::vector<std::string> extensions;
};

// NANO_VALIDATION=1 (or any value other than empty/"0") asks for validation in tools.
bool validation_requested_by_environment();

struct ValidationCounts {
  std::atomic<std::uint32_t> errors{0};
  std::atomic<std::uint32_t> warnings{0};
};

class Instance {
public:
  explicit Instance(const InstanceOptions& options = {});
  Instance(Instance&& other) noexcept;
  Instance& operator=(Instance&& other) noexcept;
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;
  ~Instance();

  VkInstance handle() const { return instance_; }
  bool validation_enabled() const { return messenger_ != VK_NULL_HANDLE; }
  std::uint32_t validation_errors() const { return counts_->errors.load(); }
  std::uint32_t validation_warnings() const { return counts_->warnings.load(); }

private:
  void destroy();

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  // Heap-allocated so the address handed to the messenger callback survives moves of Instance.
  std::unique_ptr<ValidationCounts> counts_ = std::make_unique<ValidationCounts>();
};

// A presentation surface (VK_KHR_surface) owned with the instance it was made from; destroyed
// before that instance, which the owner guarantees by declaring it after the Instance.
class Surface {
public:
  Surface() = default;
  Surface(VkInstance instance, VkSurfaceKHR surface) : instance_(instance), surface_(surface) {}
  Surface(Surface&& other) noexcept;
  Surface& operator=(Surface&& other) noexcept;
  Surface(const Surface&) = delete;
  Surface& operator=(const Surface&) = delete;
  ~Surface();

  VkSurfaceKHR handle() const { return surface_; }

private:
  VkInstance instance_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
};

}  // namespace nano::vk
