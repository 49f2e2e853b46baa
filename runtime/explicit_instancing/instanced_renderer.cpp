#include "runtime/explicit_instancing/instanced_renderer.hpp"

#include <chrono>
#include <memory>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "runtime/render/pixel_outputs.hpp"
#include "runtime/vk/buffer.hpp"
#include "runtime/vk/compute_pipeline.hpp"
#include "shared/bindings.h"
#include "shared/instanced_records.h"

extern const std::uint32_t nano_spv_instanced_comp[];
extern const std::size_t nano_spv_instanced_comp_words;

namespace nano::explicit_instancing {
namespace {

using FrameRecord = gpu::InstancedFrameRecord;

vk::ComputePipelineDesc pipeline_desc(bool counters) {
  vk::ComputePipelineDesc desc;
  desc.code = {nano_spv_instanced_comp, nano_spv_instanced_comp_words};
  desc.sets = {render::ray_query_set({gpu::NANO_IB_TLAS}, gpu::NANO_INSTANCED_BINDING_COUNT)};  // set NANO_DESCRIPTOR_SET, the only one
  desc.specialization.set_bool(gpu::NANO_SPEC_INSTANCED_COUNTERS, counters);
  return desc;
}

struct Pipeline {
  vk::ComputePipeline pipeline;
  vk::DescriptorPool pool;
  VkDescriptorSet set;
  Pipeline(const vk::Device& d, bool counters)
      : pipeline(d, pipeline_desc(counters)), pool(d, pipeline), set(pool.allocate(pipeline.set_layout(0))) {}
};

}  // namespace

struct InstancedRenderer::Impl {
  const vk::Device& device;
  InstancedScene& scene;
  glm::vec3 light;
  std::unique_ptr<Pipeline> plain, counting;
  bool counters = false;
  vk::Buffer frame_buffer;
  render::PixelOutputs outputs;

  Impl(const vk::Device& d, InstancedScene& s, const glm::vec3& l) : device(d), scene(s), plain(std::make_unique<Pipeline>(d, false)) {
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
    if (counters && !counting) counting = std::make_unique<Pipeline>(device, true);
    Pipeline& p = counters ? *counting : *plain;
    // Rewritten every frame: prepare() may have replaced the TLAS.
    scene.write_descriptors(p.set);
    vk::write_storage_buffer(device.handle(), p.set, gpu::NANO_IB_FRAME, frame_buffer);
    outputs.bind(device, p.set, {gpu::NANO_IB_HITS, gpu::NANO_IB_COLOURS, gpu::NANO_IB_COUNTERS}, std::uint64_t(w) * h, counters);
    vk::dispatch_pixels_and_wait(device, p.pipeline, p.set, w, h, gpu::NANO_WORKGROUP_SIZE);
    InstancedFrame out;
    out.width = w, out.height = h;
    outputs.read(out.hits, out.rgba, out.counters);
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
  }
};

InstancedRenderer::InstancedRenderer(const vk::Device& device, InstancedScene& scene, const glm::vec3& light)
    : impl_(std::make_unique<Impl>(device, scene, light)) {}
InstancedRenderer::~InstancedRenderer() = default;
InstancedFrame InstancedRenderer::render(const gpu::Camera& camera) { return impl_->render(camera); }
void InstancedRenderer::set_counters(bool on) { impl_->counters = on; }

}  // namespace nano::explicit_instancing
