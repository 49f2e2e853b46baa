#include "runtime/render/pixel_outputs.hpp"

#include <algorithm>

#include "shared/ray_counters.h"

namespace nano::render {

std::vector<vk::DescriptorBinding> ray_query_set(std::initializer_list<std::uint32_t> structures, std::uint32_t count) {
  std::vector<vk::DescriptorBinding> set;
  for (std::uint32_t b = 0; b < count; ++b)
    set.push_back({b, std::find(structures.begin(), structures.end(), b) != structures.end()
                          ? VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR
                          : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  return set;
}

void PixelOutputs::bind(const vk::Device& device, VkDescriptorSet set, const PixelOutputBindings& bindings,
                        std::uint64_t pixels, bool counters) {
  constexpr VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  if (pixels != pixels_ || !hits_.handle()) {
    hits_ = vk::Buffer(device, pixels * sizeof(gpu::PixelHit), usage, vk::MemoryUse::HostVisible);
    colours_ = vk::Buffer(device, pixels * 4, usage, vk::MemoryUse::HostVisible);
    counter_words_ = vk::Buffer();
    pixels_ = pixels;
  }
  const VkDeviceSize counter_bytes = counters ? pixels * gpu::NANO_RAY_COUNTER_COUNT * 4 : 4;
  if (counter_words_.size() != counter_bytes)
    counter_words_ = vk::Buffer(device, counter_bytes, usage, vk::MemoryUse::HostVisible);
  counters_ = counters;
  vk::write_storage_buffer(device.handle(), set, bindings.hits, hits_);
  vk::write_storage_buffer(device.handle(), set, bindings.colours, colours_);
  vk::write_storage_buffer(device.handle(), set, bindings.counters, counter_words_);
}

void PixelOutputs::read(std::vector<gpu::PixelHit>& hits, std::vector<std::uint32_t>& rgba,
                        std::vector<std::uint32_t>& counters) const {
  hits.resize(pixels_);
  rgba.resize(pixels_);
  hits_.read(std::as_writable_bytes(std::span(hits)));
  colours_.read(std::as_writable_bytes(std::span(rgba)));
  counters.clear();
  if (!counters_) return;
  counters.resize(pixels_ * gpu::NANO_RAY_COUNTER_COUNT);
  counter_words_.read(std::as_writable_bytes(std::span(counters)));
}

}  // namespace nano::render
