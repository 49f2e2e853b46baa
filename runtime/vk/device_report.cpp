#include "runtime/vk/device_report.hpp"

#include <cstring>

#include "runtime/vk/error.hpp"

namespace nano::vk {
namespace {

std::vector<VkExtensionProperties> device_extensions(VkPhysicalDevice device) {
  std::uint32_t count = 0;
  check(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr), "vkEnumerateDeviceExtensionProperties");
  std::vector<VkExtensionProperties> extensions(count);
  check(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()),
        "vkEnumerateDeviceExtensionProperties");
  extensions.resize(count);
  return extensions;
}

bool has_extension(const std::vector<VkExtensionProperties>& extensions, const char* name) {
  for (const auto& e : extensions)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

std::uint32_t find_compute_queue_family(VkPhysicalDevice device) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (std::uint32_t i = 0; i < count; ++i)
    if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && families[i].queueCount > 0) return i;
  return kNoQueueFamily;
}

}  // namespace

const char* device_type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

std::string api_version_string(std::uint32_t version) {
  return std::to_string(VK_API_VERSION_MAJOR(version)) + "." + std::to_string(VK_API_VERSION_MINOR(version)) + "." +
         std::to_string(VK_API_VERSION_PATCH(version));
}

std::vector<VkPhysicalDevice> enumerate_physical_devices(VkInstance instance) {
  std::uint32_t count = 0;
  const VkResult result = vkEnumeratePhysicalDevices(instance, &count, nullptr);
  // The loader answers this way when no installed driver finds its hardware.
  if (result == VK_ERROR_INITIALIZATION_FAILED)
    throw DeviceSelectionError("no Vulkan physical devices found: vkEnumeratePhysicalDevices failed with "
                               "VK_ERROR_INITIALIZATION_FAILED (is a Vulkan driver such as mesa-vulkan-drivers installed?)");
  check(result, "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devices(count);
  check(vkEnumeratePhysicalDevices(instance, &count, devices.data()), "vkEnumeratePhysicalDevices");
  devices.resize(count);
  return devices;
}

DeviceReport survey_device(VkPhysicalDevice device, std::uint32_t index) {
  DeviceReport report;
  report.index = index;

  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(device, &properties);
  report.name = properties.deviceName;
  report.type = properties.deviceType;
  report.api_version = properties.apiVersion;

  const auto extensions = device_extensions(device);
  for (const char* name : kRequiredDeviceExtensions)
    if (!has_extension(extensions, name)) report.missing.emplace_back(name);

  report.compute_queue_family = find_compute_queue_family(device);
  if (report.compute_queue_family == kNoQueueFamily) report.missing.emplace_back("a queue family with VK_QUEUE_COMPUTE_BIT");

  // Vulkan 1.2 structures (driver properties, Vulkan12Features) may only be chained on 1.2 devices.
  if (properties.apiVersion < VK_API_VERSION_1_2) {
    report.missing.insert(report.missing.begin(), "Vulkan 1.2 (device offers " + api_version_string(properties.apiVersion) + ")");
    VkPhysicalDeviceFeatures features{};
    vkGetPhysicalDeviceFeatures(device, &features);
    report.shader_int64 = features.shaderInt64 == VK_TRUE;
    return report;
  }

  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 properties2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  properties2.pNext = &driver;
  vkGetPhysicalDeviceProperties2(device, &properties2);
  report.driver_name = driver.driverName;
  report.driver_info = driver.driverInfo;

  // Extension feature structs may only be chained when the extension exists.
  VkPhysicalDeviceVulkan12Features vulkan12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR acceleration{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceRayQueryFeaturesKHR ray_query{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  VkPhysicalDeviceFeatures2 features2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features2.pNext = &vulkan12;
  void** tail = &vulkan12.pNext;
  const bool has_acceleration = has_extension(extensions, VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME);
  report.external_memory_host = has_extension(extensions, VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME);
  const bool has_ray_query = has_extension(extensions, VK_KHR_RAY_QUERY_EXTENSION_NAME);
  if (has_acceleration) {
    *tail = &acceleration;
    tail = &acceleration.pNext;
  }
  if (has_ray_query) {
    *tail = &ray_query;
    tail = &ray_query.pNext;
  }
  vkGetPhysicalDeviceFeatures2(device, &features2);
  report.shader_int64 = features2.features.shaderInt64 == VK_TRUE;

  if (!vulkan12.bufferDeviceAddress) report.missing.emplace_back("VkPhysicalDeviceVulkan12Features::bufferDeviceAddress");
  if (has_acceleration && !acceleration.accelerationStructure)
    report.missing.emplace_back("VkPhysicalDeviceAccelerationStructureFeaturesKHR::accelerationStructure");
  if (has_ray_query && !ray_query.rayQuery) report.missing.emplace_back("VkPhysicalDeviceRayQueryFeaturesKHR::rayQuery");
  return report;
}

}  // namespace nano::vk
