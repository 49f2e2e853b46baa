#pragma once
// What one physical device is and what it lacks for the ray-query renderer. Plain data, so the
// selection policy (device_selection.hpp) can be tested without any Vulkan device.
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace nano::vk {

inline constexpr std::uint32_t kNoQueueFamily = ~0u;

// Device extensions the renderer cannot run without.
inline constexpr const char* kRequiredDeviceExtensions[] = {
    VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
    VK_KHR_RAY_QUERY_EXTENSION_NAME,
    VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME,
};

struct DeviceReport {
  std::uint32_t index = 0;  // position in vkEnumeratePhysicalDevices order
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  std::uint32_t api_version = 0;
  std::string driver_name;  // VkPhysicalDeviceDriverProperties; empty before Vulkan 1.2
  std::string driver_info;
  std::uint32_t compute_queue_family = kNoQueueFamily;
  // Optional capabilities the renderer enables when present.
  bool shader_int64 = false;
  bool external_memory_host = false;  // VK_EXT_external_memory_host: package pages imported, not copied
  // Exact names of each missing requirement: "Vulkan 1.2", extension names, or
  // "<FeatureStruct>::<member>" for features. Empty means the device qualifies.
  std::vector<std::string> missing;

  bool qualifies() const { return missing.empty(); }
};

const char* device_type_name(VkPhysicalDeviceType type);
std::string api_version_string(std::uint32_t version);  // "1.3.278"

// Queries one device; never throws for missing capabilities, only for failed queries.
DeviceReport survey_device(VkPhysicalDevice device, std::uint32_t index);
std::vector<VkPhysicalDevice> enumerate_physical_devices(VkInstance instance);

}  // namespace nano::vk
