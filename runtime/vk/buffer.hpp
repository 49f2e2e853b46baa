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

  VkBuffer handle() const { return buffer_.get(); }
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
};

}  // namespace nano::vk
