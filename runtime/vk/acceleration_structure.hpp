#pragma once
// Bottom-level structures over AABBs (spheres, prisms, boxes are tested in the shader) and
// top-level structures over instances, built on the device (lavapipe has no host builds).
#include <cstdint>
#include <functional>
#include <span>
#include <utility>

#include <glm/mat4x4.hpp>
#include <vulkan/vulkan.h>

#include "runtime/vk/buffer.hpp"
#include "runtime/vk/device.hpp"
#include "runtime/vk/handle.hpp"

namespace nano::vk {

class AccelerationStructure {
public:
  AccelerationStructure() = default;
  AccelerationStructure(Buffer storage, DeviceHandle<VkAccelerationStructureKHR> handle, VkDeviceAddress address,
                        VkDeviceSize scratch_size = 0)
      : storage_(std::move(storage)), handle_(std::move(handle)), address_(address), scratch_size_(scratch_size) {}
  AccelerationStructure(AccelerationStructure&&) noexcept = default;
  AccelerationStructure& operator=(AccelerationStructure&& other) noexcept {
    if (this != &other) {
      handle_ = std::move(other.handle_);  // the old handle goes before the storage it lives in
      storage_ = std::move(other.storage_);
      address_ = std::exchange(other.address_, 0);
      scratch_size_ = std::exchange(other.scratch_size_, 0);
    }
    return *this;
  }

  VkAccelerationStructureKHR handle() const { return handle_.get(); }
  VkDeviceAddress address() const { return address_; }  // for instance records and GLSL uint64 casts
  VkDeviceSize size() const { return storage_.size(); }
  // The scratch memory its build needed (freed when the build finished).
  VkDeviceSize scratch_size() const { return scratch_size_; }

private:
  Buffer storage_;                                    // declared first: outlives the handle
  DeviceHandle<VkAccelerationStructureKHR> handle_;
  VkDeviceAddress address_ = 0;
  VkDeviceSize scratch_size_ = 0;
};

// Usage flags of buffers read by builds (AABBs, instance records).
inline constexpr VkBufferUsageFlags kBuildInputUsage =
    VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;

struct AabbGeometry {
  VkDeviceAddress aabbs = 0;  // tightly packed VkAabbPositionsKHR unless stride says otherwise
  std::uint32_t count = 0;
  VkDeviceSize stride = sizeof(VkAabbPositionsKHR);
  // Non-opaque so candidates reach the shader's rayQueryProceedEXT loop for the exact test.
  VkGeometryFlagsKHR flags = 0;
};

// Both builds wait for completion and end with a barrier that makes the result visible to later
// builds and to compute shaders.
AccelerationStructure build_bottom_level(const Device& device, const AabbGeometry& geometry);
AccelerationStructure build_top_level(const Device& device, VkDeviceAddress instances, std::uint32_t count);
AccelerationStructure build_top_level(const Device& device, std::span<const VkAccelerationStructureInstanceKHR> instances);
// As above; `also` records more commands into the same submission after the build (one wait for
// both: the flat level uploads its copy records beside its rebuild).
AccelerationStructure build_top_level(const Device& device, VkDeviceAddress instances, std::uint32_t count,
                                      const std::function<void(VkCommandBuffer)>& also);
// The storage a top-level structure over `count` instances needs on this device (no build).
VkDeviceSize top_level_size(const Device& device, std::uint32_t count);

// Row-major 3x4 object-to-world matrix from a GLM affine transform (last row 0 0 0 1 is dropped).
VkTransformMatrixKHR to_transform_matrix(const glm::dmat4& object_to_world);

VkAccelerationStructureInstanceKHR make_instance(const AccelerationStructure& bottom_level, const glm::dmat4& object_to_world,
                                                 std::uint32_t custom_index, std::uint8_t mask = 0xFF);

}  // namespace nano::vk
