#pragma once
// Compute pipelines from SPIR-V embedded at build time (nano_spv_<name>), with descriptor set
// layouts, push constants and specialization constants (effects that are off cost nothing).
#include <cstddef>
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "runtime/vk/acceleration_structure.hpp"
#include "runtime/vk/buffer.hpp"
#include "runtime/vk/device.hpp"
#include "runtime/vk/handle.hpp"

namespace nano::vk {

struct SpirvCode {
  const std::uint32_t* words = nullptr;
  std::size_t word_count = 0;
};

// Values for `layout(constant_id = N) const ...` (and local_size_x_id) in the shader.
class SpecializationConstants {
public:
  SpecializationConstants& set(std::uint32_t id, std::uint32_t value);
  SpecializationConstants& set(std::uint32_t id, std::int32_t value);
  SpecializationConstants& set(std::uint32_t id, float value);
  SpecializationConstants& set_bool(std::uint32_t id, bool value);  // GLSL bool is a 32-bit VkBool32

  bool empty() const { return entries_.empty(); }
  // Points into this object: valid while it lives and is not modified.
  VkSpecializationInfo info() const;

private:
  SpecializationConstants& set_word(std::uint32_t id, std::uint32_t bits);

  std::vector<VkSpecializationMapEntry> entries_;
  std::vector<std::uint32_t> data_;
};

struct DescriptorBinding {
  std::uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  std::uint32_t count = 1;
};

struct ComputePipelineDesc {
  SpirvCode code;
  const char* entry_point = "main";
  std::vector<std::vector<DescriptorBinding>> sets;  // sets[i] is descriptor set i
  std::uint32_t push_constant_bytes = 0;
  SpecializationConstants specialization;
};

class ComputePipeline {
public:
  ComputePipeline(const Device& device, const ComputePipelineDesc& desc);

  VkPipeline handle() const { return pipeline_.get(); }
  VkPipelineLayout layout() const { return layout_.get(); }
  VkDescriptorSetLayout set_layout(std::size_t set) const { return set_layouts_.at(set).get(); }
  const std::vector<std::vector<DescriptorBinding>>& sets() const { return sets_; }

private:
  std::vector<std::vector<DescriptorBinding>> sets_;
  std::vector<DeviceHandle<VkDescriptorSetLayout>> set_layouts_;
  DeviceHandle<VkPipelineLayout> layout_;
  DeviceHandle<VkPipeline> pipeline_;
};

// A pool sized for `copies` of every descriptor set of one pipeline; the sets die with the pool.
class DescriptorPool {
public:
  DescriptorPool(const Device& device, const ComputePipeline& pipeline, std::uint32_t copies = 1);
  VkDescriptorSet allocate(VkDescriptorSetLayout layout);

private:
  DeviceHandle<VkDescriptorPool> pool_;
};

void write_storage_buffer(VkDevice device, VkDescriptorSet set, std::uint32_t binding, const Buffer& buffer);
void write_acceleration_structure(VkDevice device, VkDescriptorSet set, std::uint32_t binding,
                                  const AccelerationStructure& structure);

// One invocation per pixel of a width × height image (workgroups of `workgroup`² invocations) with
// set 0 bound, then a barrier that makes the shader's writes visible to host reads; waits for it.
void dispatch_pixels_and_wait(const Device& device, const ComputePipeline& pipeline, VkDescriptorSet set,
                              std::uint32_t width, std::uint32_t height, std::uint32_t workgroup);

// The same for the width × height pixels from (x, y) of a larger image, handing (x, y) to the
// shader as an 8-byte push constant (the pipeline's layout must declare one).
void dispatch_region_and_wait(const Device& device, const ComputePipeline& pipeline, VkDescriptorSet set, std::uint32_t x,
                              std::uint32_t y, std::uint32_t width, std::uint32_t height, std::uint32_t workgroup);

}  // namespace nano::vk
