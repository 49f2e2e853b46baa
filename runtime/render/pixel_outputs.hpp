#pragma once
// What a per-pixel ray-query pipeline writes (render.comp and instanced.comp alike): hit ids and
// depth, an RGBA8 colour, and — when its counters specialization constant is on — a row of work
// counters per pixel (shared/ray_counters.h). Owns the host-visible buffers, binds them and reads
// them back, so the two renderers share one way of doing it.
#include <cstdint>
#include <initializer_list>
#include <vector>

#include "runtime/vk/buffer.hpp"
#include "runtime/vk/compute_pipeline.hpp"
#include "runtime/vk/device.hpp"
#include "shared/camera.h"

namespace nano::render {

// Bindings of one pixel pipeline's outputs in its set 0.
struct PixelOutputBindings {
  std::uint32_t hits, colours, counters;
};

// Bindings 0 .. `count` − 1, acceleration structures at `structures` and storage buffers elsewhere:
// the layout of set 0 of both pixel pipelines.
std::vector<vk::DescriptorBinding> ray_query_set(std::initializer_list<std::uint32_t> structures, std::uint32_t count);

class PixelOutputs {
public:
  // Sizes the buffers for `pixels` (kept while unchanged) and writes them into `set`. Without
  // counters the counter binding gets a one-word buffer the shader never writes.
  void bind(const vk::Device& device, VkDescriptorSet set, const PixelOutputBindings& bindings, std::uint64_t pixels,
            bool counters);

  // Reads back what the last dispatch wrote; `counters` stays empty when they were off.
  void read(std::vector<gpu::PixelHit>& hits, std::vector<std::uint32_t>& rgba, std::vector<std::uint32_t>& counters) const;

private:
  std::uint64_t pixels_ = 0;
  bool counters_ = false;
  vk::Buffer hits_, colours_, counter_words_;
};

}  // namespace nano::render
