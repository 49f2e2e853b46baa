#pragma once
// A VkBuffer with its own memory allocation. Buffers with VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT
// get memory allocated with the device-address flag and expose address(); host-visible buffers stay
// mapped for their whole life.
#include <cstddef>
#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

#include "runtime/vk/device.hpp"
#include "runtime/vk/handle.hpp"

namespace nano::vk {

enum class MemoryUse {
  DeviceLocal,  // fastest for the GPU; filled through a staging copy
  HostVisible,  // HOST_VISIBLE | HOST_COHERENT: uploads written and results read directly
};

class Buffer {
public:
  Buffer() = default;
  Buffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use);
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;

  // A buffer holding `bytes`. DeviceLocal buffers are filled by a staging copy (TRANSFER_DST is
  // added to `usage`), so the data is in place when this returns.
  static Buffer with_data(const Device& device, std::span<const std::byte> bytes, VkBufferUsageFlags usage, MemoryUse use);

  // A buffer over host memory the caller keeps alive and unchanged for the buffer's life (a section
  // of a memory-mapped package), imported with VK_EXT_external_memory_host: no copy. The imported
  // range is `bytes` widened to the device's import alignment, so it must lie in pages the process
  // has mapped; view_offset()/view_range() then select `bytes` within it. Throws VulkanError when the
  // device refuses the import (the caller falls back to with_data).
  static Buffer import_host(const Device& device, std::span<const std::byte> bytes, VkBufferUsageFlags usage);

  // A device-local copy of `source`'s view (made on the device; for an imported buffer the copy
  // reads the host pages directly, with no staging buffer in between).
  static Buffer device_copy(const Device& device, const Buffer& source, VkBufferUsageFlags usage);
  // Records the copy of `source`'s bound part into `destination` (at least as large) and a barrier
  // after which any later command may read it.
  static void record_copy(VkCommandBuffer commands, const Buffer& source, const Buffer& destination);

  VkBuffer handle() const { return buffer_.get(); }
  // The part of the buffer descriptors bind (everything, except for imported buffers).
  VkDeviceSize view_offset() const { return view_offset_; }
  VkDeviceSize view_range() const { return view_range_; }
  VkDeviceSize size() const { return size_; }
  VkDeviceAddress address() const { return address_; }  // 0 without SHADER_DEVICE_ADDRESS usage
  bool host_visible() const { return mapped_ != nullptr; }

  // Host access; throw for DeviceLocal buffers and out-of-range spans.
  void write(std::span<const std::byte> bytes, VkDeviceSize offset = 0);
  void read(std::span<std::byte> bytes, VkDeviceSize offset = 0) const;

private:
  void check_host_range(std::size_t count, VkDeviceSize offset) const;

  DeviceHandle<VkDeviceMemory> memory_;  // declared first so it is freed after the buffer
  DeviceHandle<VkBuffer> buffer_;
  VkDeviceSize size_ = 0;
  VkDeviceAddress address_ = 0;
  void* mapped_ = nullptr;  // unmapped implicitly by vkFreeMemory
  VkDeviceSize view_offset_ = 0;
  VkDeviceSize view_range_ = VK_WHOLE_SIZE;
};

}  // namespace nano::vk
