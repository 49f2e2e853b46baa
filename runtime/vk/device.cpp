#include "runtime/vk/device.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "runtime/vk/device_selection.hpp"
#include "runtime/vk/error.hpp"
#include "runtime/vk/pipeline_cache.hpp"

namespace nano::vk {
namespace {

bool has_device_extension(VkPhysicalDevice device, const std::string& name) {
  std::uint32_t count = 0;
  check(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr), "vkEnumerateDeviceExtensionProperties");
  std::vector<VkExtensionProperties> extensions(count);
  check(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()), "vkEnumerateDeviceExtensionProperties");
  for (const auto& e : extensions)
    if (name == e.extensionName) return true;
  return false;
}

// One queue does everything (ray-query dispatch, upload into the swapchain image, the overlay's
// draw, present), so frames need no queue-ownership transfers.
std::uint32_t find_present_queue_family(VkPhysicalDevice device, VkSurfaceKHR surface) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  const VkQueueFlags needed = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  for (std::uint32_t i = 0; i < count; ++i) {
    if ((families[i].queueFlags & needed) != needed || families[i].queueCount == 0) continue;
    VkBool32 present = VK_FALSE;
    check(vkGetPhysicalDeviceSurfaceSupportKHR(device, i, surface, &present), "vkGetPhysicalDeviceSurfaceSupportKHR");
    if (present) return i;
  }
  return kNoQueueFamily;
}

template <typename Pfn>
Pfn load(VkDevice device, const char* name) {
  auto function = reinterpret_cast<Pfn>(vkGetDeviceProcAddr(device, name));
  if (function == nullptr) throw std::runtime_error(std::string("vkGetDeviceProcAddr returned no ") + name);
  return function;
}

// The required extensions, host-memory import when the device has it, and the caller's extras.
// Points into `options`, which must outlive the result.
std::vector<const char*> device_extensions(const DeviceReport& report, const DeviceOptions& options) {
  std::vector<const char*> extensions(std::begin(kRequiredDeviceExtensions), std::end(kRequiredDeviceExtensions));
  if (report.external_memory_host) {
    extensions.push_back(VK_KHR_EXTERNAL_MEMORY_EXTENSION_NAME);  // core in 1.1; listed for 1.0-era loaders
    extensions.push_back(VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME);
  }
  for (const auto& name : options.extensions)
    if (std::find_if(extensions.begin(), extensions.end(), [&](const char* e) { return name == e; }) == extensions.end())
      extensions.push_back(name.c_str());
  return extensions;
}

// A logical device with ray queries, acceleration structures and buffer device addresses, and one
// queue of the report's compute family.
VkDevice create_device(VkPhysicalDevice physical_device, const DeviceReport& report, const DeviceOptions& options) {
  VkPhysicalDeviceRayQueryFeaturesKHR ray_query{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  ray_query.rayQuery = VK_TRUE;
  VkPhysicalDeviceAccelerationStructureFeaturesKHR acceleration{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  acceleration.accelerationStructure = VK_TRUE;
  acceleration.pNext = &ray_query;
  VkPhysicalDeviceVulkan12Features vulkan12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  vulkan12.bufferDeviceAddress = VK_TRUE;
  vulkan12.pNext = &acceleration;
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.features.shaderInt64 = report.shader_int64 ? VK_TRUE : VK_FALSE;
  features.pNext = &vulkan12;

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue_info.queueFamilyIndex = report.compute_queue_family;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;

  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.pNext = &features;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  const std::vector<const char*> extensions = device_extensions(report, options);
  info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VkDevice device = VK_NULL_HANDLE;
  check(vkCreateDevice(physical_device, &info, nullptr, &device), "vkCreateDevice");
  return device;
}

AccelerationStructureFunctions load_acceleration_structure_functions(VkDevice device) {
  AccelerationStructureFunctions f;
  f.create = load<PFN_vkCreateAccelerationStructureKHR>(device, "vkCreateAccelerationStructureKHR");
  f.destroy = load<PFN_vkDestroyAccelerationStructureKHR>(device, "vkDestroyAccelerationStructureKHR");
  f.get_build_sizes = load<PFN_vkGetAccelerationStructureBuildSizesKHR>(device, "vkGetAccelerationStructureBuildSizesKHR");
  f.cmd_build = load<PFN_vkCmdBuildAccelerationStructuresKHR>(device, "vkCmdBuildAccelerationStructuresKHR");
  f.get_device_address =
      load<PFN_vkGetAccelerationStructureDeviceAddressKHR>(device, "vkGetAccelerationStructureDeviceAddressKHR");
  return f;
}

}  // namespace

Device::Device(VkPhysicalDevice physical_device, DeviceReport report, const DeviceOptions& options)
    : physical_device_(physical_device), report_(std::move(report)) {
  if (!report_.qualifies())
    throw DeviceSelectionError("device cannot run ray queries: " + report_.name + " lacks " + report_.missing.front());

  acceleration_properties_.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR;
  VkPhysicalDeviceExternalMemoryHostPropertiesEXT host_properties{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_MEMORY_HOST_PROPERTIES_EXT};
  VkPhysicalDeviceProperties2 properties2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  properties2.pNext = &acceleration_properties_;
  if (report_.external_memory_host) acceleration_properties_.pNext = &host_properties;
  vkGetPhysicalDeviceProperties2(physical_device_, &properties2);
  properties_ = properties2.properties;
  acceleration_properties_.pNext = nullptr;
  host_import_alignment_ = host_properties.minImportedHostPointerAlignment;
  vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory_properties_);

  device_ = create_device(physical_device_, report_, options);

  try {
    vkGetDeviceQueue(device_, report_.compute_queue_family, 0, &queue_);
    as_functions_ = load_acceleration_structure_functions(device_);

    if (report_.external_memory_host)
      get_host_pointer_properties_ =
          load<PFN_vkGetMemoryHostPointerPropertiesEXT>(device_, "vkGetMemoryHostPointerPropertiesEXT");

    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pool_info.queueFamilyIndex = report_.compute_queue_family;
    VkCommandPool pool = VK_NULL_HANDLE;
    check(vkCreateCommandPool(device_, &pool_info, nullptr, &pool), "vkCreateCommandPool");
    command_pool_ = DeviceHandle<VkCommandPool>(device_, pool, vkDestroyCommandPool);

    if (options.persistent_pipeline_cache) {
      const PipelineCacheKey key = pipeline_cache_key(physical_device_, options.shader_hash);
      pipeline_cache_ = std::make_unique<PipelineCache>(device_, key, pipeline_cache_file(key));
    }
  } catch (...) {
    command_pool_.reset();
    vkDestroyDevice(device_, nullptr);
    throw;
  }
}

Device::Device(Device&& other) noexcept
    : physical_device_(other.physical_device_),
      report_(std::move(other.report_)),
      properties_(other.properties_),
      acceleration_properties_(other.acceleration_properties_),
      memory_properties_(other.memory_properties_),
      device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      queue_(other.queue_),
      as_functions_(other.as_functions_),
      get_host_pointer_properties_(other.get_host_pointer_properties_),
      host_import_alignment_(other.host_import_alignment_),
      command_pool_(std::move(other.command_pool_)),
      queue_mutex_(std::move(other.queue_mutex_)),
      pipeline_cache_(std::move(other.pipeline_cache_)) {}

Device::~Device() {
  if (device_ == VK_NULL_HANDLE) return;
  // Destructors must not throw; a lost device here changes nothing for the caller.
  vkDeviceWaitIdle(device_);
  pipeline_cache_.reset();  // saves what this run compiled
  command_pool_.reset();
  vkDestroyDevice(device_, nullptr);
}

std::uint32_t Device::find_memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required) const {
  for (std::uint32_t i = 0; i < memory_properties_.memoryTypeCount; ++i)
    if ((type_bits & (1u << i)) && (memory_properties_.memoryTypes[i].propertyFlags & required) == required) return i;
  throw std::runtime_error("no Vulkan memory type with property flags " + std::to_string(required) +
                           " among allowed types mask " + std::to_string(type_bits) + " on " + report_.name);
}

void Device::submit_once(const std::function<void(VkCommandBuffer)>& record) const {
  const std::lock_guard queue_lock(*queue_mutex_);
  VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocate.commandPool = command_pool_.get();
  allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocate.commandBufferCount = 1;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  check(vkAllocateCommandBuffers(device_, &allocate, &commands), "vkAllocateCommandBuffers");
  struct FreeOnExit {
    VkDevice device;
    VkCommandPool pool;
    VkCommandBuffer commands;
    ~FreeOnExit() { vkFreeCommandBuffers(device, pool, 1, &commands); }
  } free_on_exit{device_, command_pool_.get(), commands};

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(commands, &begin), "vkBeginCommandBuffer");
  record(commands);
  check(vkEndCommandBuffer(commands), "vkEndCommandBuffer");

  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence raw_fence = VK_NULL_HANDLE;
  check(vkCreateFence(device_, &fence_info, nullptr, &raw_fence), "vkCreateFence");
  DeviceHandle<VkFence> fence(device_, raw_fence, vkDestroyFence);

  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands;
  check(vkQueueSubmit(queue_, 1, &submit, fence.get()), "vkQueueSubmit");
  check(vkWaitForFences(device_, 1, &raw_fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
}

VkPipelineCache Device::pipeline_cache() const { return pipeline_cache_ ? pipeline_cache_->handle() : VK_NULL_HANDLE; }

void Device::save_pipeline_cache() const {
  if (pipeline_cache_) pipeline_cache_->save();
}

std::string Device::description() const {
  std::string driver = report_.driver_name.empty() ? std::string("unknown driver") : report_.driver_name;
  if (!report_.driver_info.empty()) driver += ", " + report_.driver_info;
  return report_.name + " (" + driver + ", API " + api_version_string(report_.api_version) + ")";
}

Device open_ray_query_device(const Instance& instance, const std::optional<std::string>& override_spec) {
  const auto physical_devices = enumerate_physical_devices(instance.handle());
  std::vector<DeviceReport> reports;
  for (std::uint32_t i = 0; i < physical_devices.size(); ++i) reports.push_back(survey_device(physical_devices[i], i));
  const std::size_t chosen = choose_device(reports, override_spec);
  return Device(physical_devices[reports[chosen].index], reports[chosen]);
}

Device open_ray_query_device(const Instance& instance) {
  return open_ray_query_device(instance, device_override_from_environment());
}

Device open_ray_query_device(const Instance& instance, const DeviceOptions& options) {
  const auto physical_devices = enumerate_physical_devices(instance.handle());
  std::vector<DeviceReport> reports;
  for (std::uint32_t i = 0; i < physical_devices.size(); ++i) {
    DeviceReport report = survey_device(physical_devices[i], i);
    for (const auto& name : options.extensions)
      if (!has_device_extension(physical_devices[i], name)) report.missing.push_back(name);
    if (options.present_surface != VK_NULL_HANDLE) {
      const std::uint32_t family = find_present_queue_family(physical_devices[i], options.present_surface);
      if (family == kNoQueueFamily)
        report.missing.emplace_back("a queue family with graphics, compute and present support for the window");
      else
        report.compute_queue_family = family;
    }
    reports.push_back(std::move(report));
  }
  const std::size_t chosen = choose_device(reports, device_override_from_environment());
  return Device(physical_devices[reports[chosen].index], reports[chosen], options);
}

}  // namespace nano::vk
