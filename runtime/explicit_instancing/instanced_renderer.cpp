#include "runtime/explicit_instancing/instanced_renderer.hpp"

#include <chrono>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "runtime/vk/buffer.hpp"
#include "runtime/vk/compute_pipeline.hpp"
#include "shared/bindings.h"
#include "shared/instanced_records.h"

extern const std::uint32_t nano_spv_instanced_comp[];
extern const std::size_t nano_spv_instanced_comp_words;

namespace nano::instanced {
namespace {

using FrameRecord = gpu::InstancedFrameRecord;

vk::ComputePipelineDesc pipeline_desc() {
  vk::ComputePipelineDesc desc;
  desc.code = {nano_spv_instanced_comp, nano_spv_instanced_comp_words};
  std::vector<vk::DescriptorBinding> set{{gpu::NANO_IB_TLAS, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR}};
  for (std::uint32_t b = gpu::NANO_IB_TLAS + 1; b < gpu::NANO_INSTANCED_BINDING_COUNT; ++b)
    set.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  desc.sets = {set};  // set NANO_DESCRIPTOR_SET, the only one
  return desc;
}

}  // namespace

struct InstancedRenderer::Impl {
  const vk::Device& device;
  InstancedScene& scene;
  glm::vec3 light;
  vk::ComputePipeline pipeline;
  vk::DescriptorPool pool;
  VkDescriptorSet set;
  vk::Buffer frame_buffer, hit_buffer, colour_buffer;

  Impl(const vk::Device& d, InstancedScene& s, const glm::vec3& l)
      : device(d), scene(s), pipeline(d, pipeline_desc()), pool(d, pipeline), set(pool.allocate(pipeline.set_layout(0))) {
    if (!(glm::length(l) > 0)) throw std::invalid_argument("InstancedRenderer: the light direction must be non-zero");
    light = glm::normalize(l);
    frame_buffer = vk::Buffer(d, sizeof(FrameRecord), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::HostVisible);
  }

  InstancedFrame render(const gpu::Camera& camera) {
    const std::uint32_t w = camera.size.x, h = camera.size.y;
    if (w == 0 || h == 0) throw std::invalid_argument("InstancedRenderer::render: image size must be positive");
    const auto start = std::chrono::steady_clock::now();
    FrameRecord frame{};
    frame.camera = camera;
    frame.origin = glm::vec4(scene.prepare(glm::dvec3(glm::vec3(camera.position))), 0.0f);
    frame.light = glm::vec4(light, 0.0f);
    frame_buffer.write(std::as_bytes(std::span(&frame, 1)));
    const VkDeviceSize pixels = VkDeviceSize(w) * h;
    if (hit_buffer.size() != pixels * sizeof(gpu::PixelHit)) {
      hit_buffer = vk::Buffer(device, pixels * sizeof(gpu::PixelHit), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::HostVisible);
      colour_buffer = vk::Buffer(device, pixels * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::HostVisible);
    }
    // Rewritten every frame: prepare() may have replaced the TLAS.
    scene.write_descriptors(set);
    vk::write_storage_buffer(device.handle(), set, gpu::NANO_IB_FRAME, frame_buffer);
    vk::write_storage_buffer(device.handle(), set, gpu::NANO_IB_HITS, hit_buffer);
    vk::write_storage_buffer(device.handle(), set, gpu::NANO_IB_COLOURS, colour_buffer);
    vk::dispatch_pixels_and_wait(device, pipeline, set, w, h, gpu::NANO_WORKGROUP_SIZE);
    InstancedFrame out;
    out.width = w, out.height = h;
    out.hits.resize(pixels);
    out.rgba.resize(pixels);
    hit_buffer.read(std::as_writable_bytes(std::span(out.hits)));
    colour_buffer.read(std::as_writable_bytes(std::span(out.rgba)));
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
  }
};

InstancedRenderer::InstancedRenderer(const vk::Device& device, InstancedScene& scene, const glm::vec3& light)
    : impl_(std::make_unique<Impl>(device, scene, light)) {}
InstancedRenderer::~InstancedRenderer() = default;
InstancedFrame InstancedRenderer::render(const gpu::Camera& camera) { return impl_->render(camera); }

}  // namespace nano::instanced
