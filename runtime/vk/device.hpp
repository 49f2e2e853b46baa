#pragma once
// The logical device: one compute queue, a command pool for one-shot work, the KHR entry points
// loaded with vkGetDeviceProcAddr, and the limits later code needs (scratch alignment, ...).
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "runtime/vk/device_report.hpp"
#include "runtime/vk/handle.hpp"
#include "runtime/vk/instance.hpp"

namespace nano::vk {

class PipelineCache;  // runtime/vk/pipeline_cache.hpp

// Extension entry points are not exported by the loader; they are fetched per device.
struct AccelerationStructureFunctions {
  PFN_vkCreateAccelerationStructureKHR create = nullptr;
  PFN_vkDestroyAccelerationStructureKHR destroy = nullptr;
  PFN_vkGetAccelerationStructureBuildSizesKHR get_build_sizes = nullptr;
  PFN_vkCmdBuildAccelerationStructuresKHR cmd_build = nullptr;
  PFN_vkGetAccelerationStructureDeviceAddressKHR get_device_address = nullptr;
};

// What a caller needs beyond the headless renderer. The defaults open exactly the device `render`
// and `verify` use; the viewer asks for VK_KHR_swapchain and a queue that can present to its window.
struct DeviceOptions {
  std::vector<std::string> extensions;             // extra device extensions (required, not optional)
  VkSurfaceKHR present_surface = VK_NULL_HANDLE;   // when set, the one queue must also present to it
  // Keep compiled pipelines across runs in the user's cache directory (runtime/vk/pipeline_cache.hpp),
  // in a file keyed by the device and `shader_hash` (embedded_shader_hash() for this program's
  // shaders). Off by default so that tests and tools touch no files; the nanoview commands turn it
  // on unless --no-pipeline-cache. Off, pipelines are created without a VkPipelineCache.
  bool persistent_pipeline_cache = false;
  std::uint64_t shader_hash = 0;
};

class Device {
public:
  // `report.compute_queue_family` is the queue the device opens; with DeviceOptions::present_surface
  // open_ray_query_device has already replaced it by a graphics + compute + present family.
  Device(VkPhysicalDevice physical_device, DeviceReport report, const DeviceOptions& options = {});
  Device(Device&& other) noexcept;
  Device& operator=(Device&&) = delete;
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;
  ~Device();

  VkDevice handle() const { return device_; }
  VkPhysicalDevice physical_device() const { return physical_device_; }
  VkQueue queue() const { return queue_; }
  std::uint32_t queue_family() const { return report_.compute_queue_family; }
  const DeviceReport& report() const { return report_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  const VkPhysicalDeviceAccelerationStructurePropertiesKHR& acceleration_structure_properties() const {
    return acceleration_properties_;
  }
  const AccelerationStructureFunctions& acceleration_structure_functions() const { return as_functions_; }

  // VK_EXT_external_memory_host, enabled when the device has it: host pages can back buffers.
  bool host_import() const { return get_host_pointer_properties_ != nullptr; }
  VkDeviceSize host_import_alignment() const { return host_import_alignment_; }
  PFN_vkGetMemoryHostPointerPropertiesEXT host_pointer_properties_function() const { return get_host_pointer_properties_; }

  // First memory type allowed by `type_bits` that has all of `required`; throws if none.
  std::uint32_t find_memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required) const;

  // Records commands into a fresh primary command buffer, submits it and waits on a fence, holding
  // queue_mutex() throughout (the command pool and the queue are externally synchronized).
  void submit_once(const std::function<void(VkCommandBuffer)>& record) const;

  // Held by whoever uses the one queue (submit_once, a presenter's submit and present): pipelines
  // may be built, and first dispatched, on a worker thread while the main thread renders.
  std::recursive_mutex& queue_mutex() const { return *queue_mutex_; }

  // The cache pipelines are created with: VK_NULL_HANDLE unless DeviceOptions::persistent_pipeline_cache.
  VkPipelineCache pipeline_cache() const;
  // Writes the pipeline cache's file when it holds something new (the destructor does too), so a
  // process killed later keeps what it compiled. Thread-safe; never throws (PipelineCache::save).
  // const: saving changes the file, not what this device does.
  void save_pipeline_cache() const;

  // "llvmpipe (LLVM 15.0.6, 256 bits) (llvmpipe, Mesa 25.0.7, API 1.3.296)"
  std::string description() const;

private:
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  DeviceReport report_;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceAccelerationStructurePropertiesKHR acceleration_properties_{};
  VkPhysicalDeviceMemoryProperties memory_properties_{};
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  AccelerationStructureFunctions as_functions_;
  PFN_vkGetMemoryHostPointerPropertiesEXT get_host_pointer_properties_ = nullptr;
  VkDeviceSize host_import_alignment_ = 0;
  DeviceHandle<VkCommandPool> command_pool_;
  std::unique_ptr<std::recursive_mutex> queue_mutex_ = std::make_unique<std::recursive_mutex>();
  std::unique_ptr<PipelineCache> pipeline_cache_;  // null without a persistent pipeline cache
};

// Surveys every physical device, applies the selection policy (NANO_DEVICE override unless
// `override_spec` is given) and opens the chosen one.
Device open_ray_query_device(const Instance& instance, const std::optional<std::string>& override_spec);
Device open_ray_query_device(const Instance& instance);
// Same policy, but a device only qualifies when it also has `options.extensions` and, with a
// present surface, a queue family with graphics, compute and present support (both recorded in
// DeviceReport::missing, so "no device" names what each device lacks).
Device open_ray_query_device(const Instance& instance, const DeviceOptions& options);

}  // namespace nano::vk
