#pragma once
// Every VkResult is checked: a failure becomes an exception naming the call and the result code,
// so a broken driver or a bad request never shows up later as a silent wrong image.
#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

namespace nano::vk {

class VulkanError : public std::runtime_error {
public:
  VulkanError(const std::string& call, VkResult result);
  VkResult result() const { return result_; }

private:
  VkResult result_;
};

// Raised when no physical device can run the ray-query renderer, or the override names none.
class DeviceSelectionError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

const char* result_name(VkResult result);

// Success codes other than VK_SUCCESS (VK_INCOMPLETE, VK_TIMEOUT, ...) are failures here: callers
// that expect them handle the result themselves.
inline void check(VkResult result, const char* call) {
  if (result != VK_SUCCESS) throw VulkanError(call, result);
}

}  // namespace nano::vk
