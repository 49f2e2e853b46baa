#include "runtime/vk/buffer.hpp"

#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "runtime/vk/error.hpp"

namespace nano::vk {

Buffer::Buffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use) : size_(size) {
  if (size == 0) throw std::invalid_argument("nano::vk::Buffer: size must be positive");
  VkDevice vk_device = device.handle();

  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  check(vkCreateBuffer(vk_device, &info, nullptr, &buffer), "vkCreateBuffer");
  buffer_ = DeviceHandle<VkBuffer>(vk_device, buffer, vkDestroyBuffer);

  VkMemoryRequirements requirements{};
  vkGetBufferMemoryRequirements(vk_device, buffer, &requirements);
  const VkMemoryPropertyFlags properties = use == MemoryUse::HostVisible
                                               ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                               : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;

  const bool wants_address = (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) != 0;
  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  VkMemoryAllocateInfo allocate{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  allocate.pNext = wants_address ? &flags : nullptr;
  allocate.allocationSize = requirements.size;
  allocate.memoryTypeIndex = device.find_memory_type(requirements.memoryTypeBits, properties);
  VkDeviceMemory memory = VK_NULL_HANDLE;
  check(vkAllocateMemory(vk_device, &allocate, nullptr, &memory), "vkAllocateMemory");
  memory_ = DeviceHandle<VkDeviceMemory>(vk_device, memory, vkFreeMemory);
  check(vkBindBufferMemory(vk_device, buffer, memory, 0), "vkBindBufferMemory");

  if (use == MemoryUse::HostVisible) check(vkMapMemory(vk_device, memory, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
  if (wants_address) {
    VkBufferDeviceAddressInfo address_info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    address_info.buffer = buffer;
    address_ = vkGetBufferDeviceAddress(vk_device, &address_info);
  }
}

Buffer::Buffer(Buffer&& other) noexcept
    : memory_(std::move(other.memory_)),
      buffer_(std::move(other.buffer_)),
      size_(std::exchange(other.size_, 0)),
      address_(std::exchange(other.address_, 0)),
      mapped_(std::exchange(other.mapped_, nullptr)),
      view_offset_(std::exchange(other.view_offset_, 0)),
      view_range_(std::exchange(other.view_range_, VK_WHOLE_SIZE)) {}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    buffer_ = std::move(other.buffer_);
    memory_ = std::move(other.memory_);
    size_ = std::exchange(other.size_, 0);
    address_ = std::exchange(other.address_, 0);
    mapped_ = std::exchange(other.mapped_, nullptr);
    view_offset_ = std::exchange(other.view_offset_, 0);
    view_range_ = std::exchange(other.view_range_, VK_WHOLE_SIZE);
  }
  return *this;
}

Buffer Buffer::import_host(const Device& device, std::span<const std::byte> bytes, VkBufferUsageFlags usage) {
  if (!device.host_import()) throw std::logic_error("nano::vk::Buffer::import_host: the device has no VK_EXT_external_memory_host");
  if (bytes.empty()) throw std::invalid_argument("nano::vk::Buffer::import_host: nothing to import");
  const VkDeviceSize align = device.host_import_alignment();
  const auto begin = reinterpret_cast<std::uintptr_t>(bytes.data());
  const std::uintptr_t first = begin / align * align;
  const std::uintptr_t last = (begin + bytes.size() + align - 1) / align * align;
  VkDevice vk_device = device.handle();
  void* host = reinterpret_cast<void*>(first);

  VkMemoryHostPointerPropertiesEXT pointer{VK_STRUCTURE_TYPE_MEMORY_HOST_POINTER_PROPERTIES_EXT};
  check(device.host_pointer_properties_function()(vk_device, VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT, host,
                                                  &pointer),
        "vkGetMemoryHostPointerPropertiesEXT");

  Buffer buffer;
  buffer.size_ = last - first;
  VkExternalMemoryBufferCreateInfo external{VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_BUFFER_CREATE_INFO};
  external.handleTypes = VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.pNext = &external;
  info.size = buffer.size_;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer raw = VK_NULL_HANDLE;
  check(vkCreateBuffer(vk_device, &info, nullptr, &raw), "vkCreateBuffer (host import)");
  buffer.buffer_ = DeviceHandle<VkBuffer>(vk_device, raw, vkDestroyBuffer);

  VkMemoryRequirements requirements{};
  vkGetBufferMemoryRequirements(vk_device, raw, &requirements);
  const std::uint32_t types = requirements.memoryTypeBits & pointer.memoryTypeBits;
  if (types == 0) throw VulkanError("vkGetMemoryHostPointerPropertiesEXT (no memory type fits the buffer)", VK_ERROR_INVALID_EXTERNAL_HANDLE);
  VkImportMemoryHostPointerInfoEXT import{VK_STRUCTURE_TYPE_IMPORT_MEMORY_HOST_POINTER_INFO_EXT};
  import.handleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT;
  import.pHostPointer = host;
  VkMemoryAllocateInfo allocate{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  allocate.pNext = &import;
  allocate.allocationSize = buffer.size_;
  allocate.memoryTypeIndex = device.find_memory_type(types, 0);
  VkDeviceMemory memory = VK_NULL_HANDLE;
  check(vkAllocateMemory(vk_device, &allocate, nullptr, &memory), "vkAllocateMemory (host import)");
  buffer.memory_ = DeviceHandle<VkDeviceMemory>(vk_device, memory, vkFreeMemory);
  check(vkBindBufferMemory(vk_device, raw, memory, 0), "vkBindBufferMemory (host import)");
  buffer.view_offset_ = begin - first;
  buffer.view_range_ = bytes.size();
  return buffer;
}

Buffer Buffer::with_data(const Device& device, std::span<const std::byte> bytes, VkBufferUsageFlags usage, MemoryUse use) {
  if (use == MemoryUse::HostVisible) {
    Buffer buffer(device, bytes.size(), usage, use);
    buffer.write(bytes);
    return buffer;
  }
  Buffer staging(device, bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::HostVisible);
  staging.write(bytes);
  return device_copy(device, staging, usage);
}

Buffer Buffer::device_copy(const Device& device, const Buffer& source, VkBufferUsageFlags usage) {
  const VkDeviceSize size = source.view_range_ == VK_WHOLE_SIZE ? source.size_ - source.view_offset_ : source.view_range_;
  Buffer buffer(device, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::DeviceLocal);
  device.submit_once([&](VkCommandBuffer commands) { record_copy(commands, source, buffer); });
  return buffer;
}

void Buffer::record_copy(VkCommandBuffer commands, const Buffer& source, const Buffer& destination) {
  const VkDeviceSize size = source.view_range_ == VK_WHOLE_SIZE ? source.size_ - source.view_offset_ : source.view_range_;
  if (size > destination.size_) throw std::invalid_argument("Buffer::record_copy: the destination is smaller than the source");
  VkBufferCopy region{source.view_offset_, 0, size};
  vkCmdCopyBuffer(commands, source.handle(), destination.handle(), 1, &region);
  // Later commands and submissions read the data in any stage (build input, shader, copy).
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &barrier, 0,
                       nullptr, 0, nullptr);
}

void Buffer::check_host_range(std::size_t count, VkDeviceSize offset) const {
  if (mapped_ == nullptr) throw std::logic_error("nano::vk::Buffer: host access to a buffer that is not host-visible");
  if (offset > size_ || count > size_ - offset)
    throw std::out_of_range("nano::vk::Buffer: host access of " + std::to_string(count) + " bytes at offset " +
                            std::to_string(offset) + " exceeds size " + std::to_string(size_));
}

void Buffer::write(std::span<const std::byte> bytes, VkDeviceSize offset) {
  check_host_range(bytes.size(), offset);
  std::memcpy(static_cast<std::byte*>(mapped_) + offset, bytes.data(), bytes.size());
}

void Buffer::read(std::span<std::byte> bytes, VkDeviceSize offset) const {
  check_host_range(bytes.size(), offset);
  std::memcpy(bytes.data(), static_cast<const std::byte*>(mapped_) + offset, bytes.size());
}

}  // namespace nano::vk
