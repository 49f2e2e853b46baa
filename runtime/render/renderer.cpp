#include "runtime/render/renderer.hpp"

#include <chrono>
#include <stdexcept>

#include "runtime/vk/compute_pipeline.hpp"
#include "shared/render_scene.h"

extern const std::uint32_t nano_spv_render_comp[];
extern const std::size_t nano_spv_render_comp_words;

namespace nano::render {
namespace {

constexpr std::uint32_t kWorkgroup = 8;  // local_size_x = local_size_y of render.comp
constexpr std::uint32_t b_frame = kSceneBindingCount, b_hits = b_frame + 1, b_colours = b_frame + 2;

vk::ComputePipelineDesc pipeline_desc(const RenderSettings& settings) {
  vk::ComputePipelineDesc desc;
  desc.code = {nano_spv_render_comp, nano_spv_render_comp_words};
  std::vector<vk::DescriptorBinding> set{{0, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR}};
  for (std::uint32_t b = 1; b <= b_colours; ++b) set.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  desc.sets = {set};
  desc.specialization.set_bool(0, settings.exact_prism);
  desc.specialization.set_bool(1, settings.replication_las && !settings.two_level);
  desc.specialization.set_bool(2, settings.two_level);
  return desc;
}

}  // namespace

struct Renderer::Impl {
  const vk::Device& device;
  GpuScene& scene;
  RenderSettings settings;
  vk::ComputePipeline pipeline;
  vk::DescriptorPool pool;
  VkDescriptorSet set;
  vk::Buffer frame_buffer, hit_buffer, colour_buffer;

  Impl(const vk::Device& d, GpuScene& s, const RenderSettings& r)
      : device(d), scene(s), settings(r), pipeline(d, pipeline_desc(r)), pool(d, pipeline), set(pool.allocate(pipeline.set_layout(0))) {
    frame_buffer = vk::Buffer(d, sizeof(gpu::RenderFrame), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::HostVisible);
  }

  Frame render(const gpu::Camera& camera) {
    const std::uint32_t w = camera.size.x, h = camera.size.y;
    if (w == 0 || h == 0) throw std::invalid_argument("render: image size must be positive");
    const auto start = std::chrono::steady_clock::now();
    scene.set_eye(glm::dvec3(glm::vec3(camera.position)));
    gpu::RenderFrame frame{};
    frame.camera = camera;
    frame.levels = glm::uvec4(scene.first_square_level(), scene.first_cube_level(), scene.molecule_type_count(),
                              scene.first_atom_square_level());
    frame.light = glm::vec4(glm::normalize(settings.light), settings.depth_cue);
    frame_buffer.write(std::as_bytes(std::span(&frame, 1)));
    const VkDeviceSize pixels = VkDeviceSize(w) * h;
    if (hit_buffer.size() != pixels * sizeof(gpu::PixelHit)) {
      hit_buffer = vk::Buffer(device, pixels * sizeof(gpu::PixelHit), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::HostVisible);
      colour_buffer = vk::Buffer(device, pixels * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::HostVisible);
    }
    scene.write_descriptors(set);
    vk::write_storage_buffer(device.handle(), set, b_frame, frame_buffer);
    vk::write_storage_buffer(device.handle(), set, b_hits, hit_buffer);
    vk::write_storage_buffer(device.handle(), set, b_colours, colour_buffer);
    device.submit_once([&](VkCommandBuffer commands) {
      vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.handle());
      vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 0, 1, &set, 0, nullptr);
      vkCmdDispatch(commands, (w + kWorkgroup - 1) / kWorkgroup, (h + kWorkgroup - 1) / kWorkgroup, 1);
      VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
      to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
      to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
      vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0,
                           nullptr, 0, nullptr);
    });
    Frame out;
    out.width = w, out.height = h;
    out.hits.resize(pixels);
    out.rgba.resize(pixels);
    hit_buffer.read(std::as_writable_bytes(std::span(out.hits)));
    colour_buffer.read(std::as_writable_bytes(std::span(out.rgba)));
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
  }
};

Renderer::Renderer(const vk::Device& device, GpuScene& scene, const RenderSettings& settings)
    : impl_(std::make_unique<Impl>(device, scene, settings)) {}
Renderer::~Renderer() = default;
Frame Renderer::render(const gpu::Camera& camera) { return impl_->render(camera); }

}  // namespace nano::render
