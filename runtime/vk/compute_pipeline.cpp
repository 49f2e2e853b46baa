#include "runtime/vk/compute_pipeline.hpp"

#include <bit>
#include <map>
#include <stdexcept>

#include "runtime/vk/error.hpp"

namespace nano::vk {

SpecializationConstants& SpecializationConstants::set_word(std::uint32_t id, std::uint32_t bits) {
  for (const auto& entry : entries_)
    if (entry.constantID == id) {
      data_[entry.offset / sizeof(std::uint32_t)] = bits;
      return *this;
    }
  entries_.push_back({id, static_cast<std::uint32_t>(data_.size() * sizeof(std::uint32_t)), sizeof(std::uint32_t)});
  data_.push_back(bits);
  return *this;
}

SpecializationConstants& SpecializationConstants::set(std::uint32_t id, std::uint32_t value) { return set_word(id, value); }
SpecializationConstants& SpecializationConstants::set(std::uint32_t id, std::int32_t value) {
  return set_word(id, std::bit_cast<std::uint32_t>(value));
}
SpecializationConstants& SpecializationConstants::set(std::uint32_t id, float value) {
  return set_word(id, std::bit_cast<std::uint32_t>(value));
}
SpecializationConstants& SpecializationConstants::set_bool(std::uint32_t id, bool value) {
  return set_word(id, value ? VK_TRUE : VK_FALSE);
}

VkSpecializationInfo SpecializationConstants::info() const {
  VkSpecializationInfo info{};
  info.mapEntryCount = static_cast<std::uint32_t>(entries_.size());
  info.pMapEntries = entries_.data();
  info.dataSize = data_.size() * sizeof(std::uint32_t);
  info.pData = data_.data();
  return info;
}

ComputePipeline::ComputePipeline(const Device& device, const ComputePipelineDesc& desc) : sets_(desc.sets) {
  if (desc.code.words == nullptr || desc.code.word_count == 0) throw std::invalid_argument("ComputePipeline: empty SPIR-V");
  VkDevice vk_device = device.handle();

  for (const auto& set : desc.sets) {
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    for (const auto& b : set) {
      VkDescriptorSetLayoutBinding binding{};
      binding.binding = b.binding;
      binding.descriptorType = b.type;
      binding.descriptorCount = b.count;
      binding.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
      bindings.push_back(binding);
    }
    VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    info.bindingCount = static_cast<std::uint32_t>(bindings.size());
    info.pBindings = bindings.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    check(vkCreateDescriptorSetLayout(vk_device, &info, nullptr, &layout), "vkCreateDescriptorSetLayout");
    set_layouts_.emplace_back(vk_device, layout, vkDestroyDescriptorSetLayout);
  }

  std::vector<VkDescriptorSetLayout> raw_layouts;
  for (const auto& layout : set_layouts_) raw_layouts.push_back(layout.get());
  VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, desc.push_constant_bytes};
  VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout_info.setLayoutCount = static_cast<std::uint32_t>(raw_layouts.size());
  layout_info.pSetLayouts = raw_layouts.data();
  layout_info.pushConstantRangeCount = desc.push_constant_bytes > 0 ? 1 : 0;
  layout_info.pPushConstantRanges = &push;
  VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
  check(vkCreatePipelineLayout(vk_device, &layout_info, nullptr, &pipeline_layout), "vkCreatePipelineLayout");
  layout_ = DeviceHandle<VkPipelineLayout>(vk_device, pipeline_layout, vkDestroyPipelineLayout);

  VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  module_info.codeSize = desc.code.word_count * sizeof(std::uint32_t);
  module_info.pCode = desc.code.words;
  VkShaderModule raw_module = VK_NULL_HANDLE;
  check(vkCreateShaderModule(vk_device, &module_info, nullptr, &raw_module), "vkCreateShaderModule");
  // Only needed while the pipeline is created.
  DeviceHandle<VkShaderModule> module(vk_device, raw_module, vkDestroyShaderModule);

  const VkSpecializationInfo specialization = desc.specialization.info();
  VkComputePipelineCreateInfo pipeline_info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  pipeline_info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipeline_info.stage.module = raw_module;
  pipeline_info.stage.pName = desc.entry_point;
  pipeline_info.stage.pSpecializationInfo = desc.specialization.empty() ? nullptr : &specialization;
  pipeline_info.layout = pipeline_layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  check(vkCreateComputePipelines(vk_device, device.pipeline_cache(), 1, &pipeline_info, nullptr, &pipeline),
        "vkCreateComputePipelines");
  pipeline_ = DeviceHandle<VkPipeline>(vk_device, pipeline, vkDestroyPipeline);
  // Now rather than at exit: a run that is killed (or crashes) later still keeps what it compiled.
  device.save_pipeline_cache();
}

DescriptorPool::DescriptorPool(const Device& device, const ComputePipeline& pipeline, std::uint32_t copies) {
  std::map<VkDescriptorType, std::uint32_t> counts;
  for (const auto& set : pipeline.sets())
    for (const auto& binding : set) counts[binding.type] += binding.count * copies;
  std::vector<VkDescriptorPoolSize> sizes;
  for (const auto& [type, count] : counts) sizes.push_back({type, count});

  VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  info.maxSets = static_cast<std::uint32_t>(pipeline.sets().size()) * copies;
  info.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  info.pPoolSizes = sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  check(vkCreateDescriptorPool(device.handle(), &info, nullptr, &pool), "vkCreateDescriptorPool");
  pool_ = DeviceHandle<VkDescriptorPool>(device.handle(), pool, vkDestroyDescriptorPool);
}

VkDescriptorSet DescriptorPool::allocate(VkDescriptorSetLayout layout) {
  VkDescriptorSetAllocateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  info.descriptorPool = pool_.get();
  info.descriptorSetCount = 1;
  info.pSetLayouts = &layout;
  VkDescriptorSet set = VK_NULL_HANDLE;
  check(vkAllocateDescriptorSets(pool_.device(), &info, &set), "vkAllocateDescriptorSets");
  return set;
}

void write_storage_buffer(VkDevice device, VkDescriptorSet set, std::uint32_t binding, const Buffer& buffer) {
  VkDescriptorBufferInfo info{buffer.handle(), buffer.view_offset(), buffer.view_range()};
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstSet = set;
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  write.pBufferInfo = &info;
  vkUpdateDescriptorSets(device, 1, &write, 0, nullptr);
}

void write_acceleration_structure(VkDevice device, VkDescriptorSet set, std::uint32_t binding,
                                  const AccelerationStructure& structure) {
  VkAccelerationStructureKHR handle = structure.handle();
  VkWriteDescriptorSetAccelerationStructureKHR info{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
  info.accelerationStructureCount = 1;
  info.pAccelerationStructures = &handle;
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.pNext = &info;
  write.dstSet = set;
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
  vkUpdateDescriptorSets(device, 1, &write, 0, nullptr);
}

namespace {

void dispatch_and_wait(const Device& device, const ComputePipeline& pipeline, VkDescriptorSet set, std::uint32_t width,
                       std::uint32_t height, std::uint32_t workgroup, const std::uint32_t* origin) {
  device.submit_once([&](VkCommandBuffer commands) {
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 0, 1, &set, 0, nullptr);
    if (origin) vkCmdPushConstants(commands, pipeline.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, 2 * sizeof *origin, origin);
    vkCmdDispatch(commands, (width + workgroup - 1) / workgroup, (height + workgroup - 1) / workgroup, 1);
    VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0,
                         nullptr, 0, nullptr);
  });
}

}  // namespace

void dispatch_pixels_and_wait(const Device& device, const ComputePipeline& pipeline, VkDescriptorSet set,
                              std::uint32_t width, std::uint32_t height, std::uint32_t workgroup) {
  dispatch_and_wait(device, pipeline, set, width, height, workgroup, nullptr);
}

void dispatch_region_and_wait(const Device& device, const ComputePipeline& pipeline, VkDescriptorSet set, std::uint32_t x,
                              std::uint32_t y, std::uint32_t width, std::uint32_t height, std::uint32_t workgroup) {
  const std::uint32_t origin[2] = {x, y};
  dispatch_and_wait(device, pipeline, set, width, height, workgroup, origin);
}

}  // namespace nano::vk
