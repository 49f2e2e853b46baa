#include "runtime/vk/acceleration_structure.hpp"

#include <stdexcept>

#include "runtime/vk/error.hpp"

namespace nano::vk {
namespace {

VkDeviceSize align_up(VkDeviceSize value, VkDeviceSize alignment) {
  return alignment <= 1 ? value : (value + alignment - 1) / alignment * alignment;
}

// One fast-trace build of one geometry; `geometry` must outlive the returned record.
VkAccelerationStructureBuildGeometryInfoKHR build_info_of(VkAccelerationStructureTypeKHR type,
                                                          const VkAccelerationStructureGeometryKHR& geometry) {
  VkAccelerationStructureBuildGeometryInfoKHR build_info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  build_info.type = type;
  build_info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
  build_info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  build_info.geometryCount = 1;
  build_info.pGeometries = &geometry;
  return build_info;
}

VkAccelerationStructureBuildSizesInfoKHR build_sizes(const Device& device, const VkAccelerationStructureBuildGeometryInfoKHR& info,
                                                     std::uint32_t primitive_count) {
  VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
  device.acceleration_structure_functions().get_build_sizes(device.handle(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR,
                                                            &info, &primitive_count, &sizes);
  return sizes;
}

AccelerationStructure build(const Device& device, VkAccelerationStructureTypeKHR type,
                            const VkAccelerationStructureGeometryKHR& geometry, std::uint32_t primitive_count,
                            const std::function<void(VkCommandBuffer)>& also = {}) {
  const auto& khr = device.acceleration_structure_functions();
  VkAccelerationStructureBuildGeometryInfoKHR build_info = build_info_of(type, geometry);
  const VkAccelerationStructureBuildSizesInfoKHR sizes = build_sizes(device, build_info, primitive_count);

  Buffer storage(device, sizes.accelerationStructureSize,
                 VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                 MemoryUse::DeviceLocal);
  VkAccelerationStructureCreateInfoKHR create{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
  create.buffer = storage.handle();
  create.size = sizes.accelerationStructureSize;
  create.type = type;
  VkAccelerationStructureKHR raw = VK_NULL_HANDLE;
  check(khr.create(device.handle(), &create, nullptr, &raw), "vkCreateAccelerationStructureKHR");
  DeviceHandle<VkAccelerationStructureKHR> handle(device.handle(), raw, khr.destroy);

  // Over-allocate so the scratch address can be rounded up to the device's required alignment.
  const VkDeviceSize alignment = device.acceleration_structure_properties().minAccelerationStructureScratchOffsetAlignment;
  Buffer scratch(device, sizes.buildScratchSize + alignment,
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT, MemoryUse::DeviceLocal);
  build_info.dstAccelerationStructure = raw;
  build_info.scratchData.deviceAddress = align_up(scratch.address(), alignment);

  VkAccelerationStructureBuildRangeInfoKHR range{};
  range.primitiveCount = primitive_count;
  const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
  device.submit_once([&](VkCommandBuffer commands) {
    khr.cmd_build(commands, 1, &build_info, &ranges);
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
    barrier.dstAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR | VK_ACCESS_SHADER_READ_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                         VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1,
                         &barrier, 0, nullptr, 0, nullptr);
    if (also) also(commands);
  });

  VkAccelerationStructureDeviceAddressInfoKHR address_info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
  address_info.accelerationStructure = raw;
  const VkDeviceAddress address = khr.get_device_address(device.handle(), &address_info);
  return AccelerationStructure(std::move(storage), std::move(handle), address, scratch.size());
}

}  // namespace

AccelerationStructure build_bottom_level(const Device& device, const AabbGeometry& geometry) {
  if (geometry.count == 0 || geometry.aabbs == 0)
    throw std::invalid_argument("build_bottom_level: needs a device address and at least one AABB");
  VkAccelerationStructureGeometryKHR vk_geometry{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  vk_geometry.geometryType = VK_GEOMETRY_TYPE_AABBS_KHR;
  vk_geometry.flags = geometry.flags;
  vk_geometry.geometry.aabbs.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_AABBS_DATA_KHR;
  vk_geometry.geometry.aabbs.data.deviceAddress = geometry.aabbs;
  vk_geometry.geometry.aabbs.stride = geometry.stride;
  return build(device, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, vk_geometry, geometry.count);
}

namespace {
VkAccelerationStructureGeometryKHR instance_geometry(VkDeviceAddress instances) {
  VkAccelerationStructureGeometryKHR vk_geometry{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  vk_geometry.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
  vk_geometry.geometry.instances.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
  vk_geometry.geometry.instances.arrayOfPointers = VK_FALSE;
  vk_geometry.geometry.instances.data.deviceAddress = instances;
  return vk_geometry;
}
}  // namespace

AccelerationStructure build_top_level(const Device& device, VkDeviceAddress instances, std::uint32_t count) {
  return build_top_level(device, instances, count, {});
}

AccelerationStructure build_top_level(const Device& device, VkDeviceAddress instances, std::uint32_t count,
                                      const std::function<void(VkCommandBuffer)>& also) {
  if (count == 0 || instances == 0) throw std::invalid_argument("build_top_level: needs a device address and at least one instance");
  return build(device, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, instance_geometry(instances), count, also);
}

VkDeviceSize top_level_size(const Device& device, std::uint32_t count) {
  const VkAccelerationStructureGeometryKHR geometry = instance_geometry(0);
  return build_sizes(device, build_info_of(VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, geometry), count).accelerationStructureSize;
}

AccelerationStructure build_top_level(const Device& device, std::span<const VkAccelerationStructureInstanceKHR> instances) {
  // The instance buffer only has to live until the build has finished, which build() waits for.
  const Buffer records = Buffer::with_data(device, std::as_bytes(instances), kBuildInputUsage, MemoryUse::DeviceLocal);
  return build_top_level(device, records.address(), static_cast<std::uint32_t>(instances.size()));
}

VkTransformMatrixKHR to_transform_matrix(const glm::dmat4& object_to_world) {
  VkTransformMatrixKHR matrix{};
  // GLM is column-major: m[column][row].
  for (int row = 0; row < 3; ++row)
    for (int column = 0; column < 4; ++column) matrix.matrix[row][column] = static_cast<float>(object_to_world[column][row]);
  return matrix;
}

VkAccelerationStructureInstanceKHR make_instance(const AccelerationStructure& bottom_level, const glm::dmat4& object_to_world,
                                                 std::uint32_t custom_index, std::uint8_t mask) {
  if (custom_index >= (1u << 24)) throw std::invalid_argument("make_instance: custom index must fit in 24 bits");
  VkAccelerationStructureInstanceKHR instance{};
  instance.transform = to_transform_matrix(object_to_world);
  instance.instanceCustomIndex = custom_index;
  instance.mask = mask;
  instance.instanceShaderBindingTableRecordOffset = 0;
  instance.flags = 0;
  instance.accelerationStructureReference = bottom_level.address();
  return instance;
}

}  // namespace nano::vk
