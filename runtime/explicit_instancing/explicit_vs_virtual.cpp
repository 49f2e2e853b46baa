#include "runtime/explicit_instancing/explicit_vs_virtual.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "runtime/bench/frame_stats.hpp"
#include "runtime/explicit_instancing/instanced_renderer.hpp"
#include "runtime/render/renderer.hpp"

namespace nano::explicit_instancing {

oracle::CompareResult compare_hits(std::vector<gpu::PixelHit> reference, const std::vector<gpu::PixelHit>& test) {
  for (gpu::PixelHit& h : reference) {
    h.compartment_instance = h.element = h.kind = h.instance = gpu::kNoHit;
    h.cell = glm::ivec4(-1);
  }
  return oracle::compare_images(reference, test, std::uint32_t(reference.size()), 1, 0);
}

nlohmann::json ExplicitVsVirtual::to_json() const {
  return {{"explicit_seconds_median", explicit_seconds_median},
          {"virtual_seconds_median", virtual_seconds_median},
          {"frame_time_ratio_explicit_over_virtual",
           virtual_seconds_median > 0 ? explicit_seconds_median / virtual_seconds_median : 0.0},
          {"explicit_device_bytes", explicit_device_bytes},
          {"virtual_device_bytes", virtual_device_bytes},
          {"copies", copies},
          {"agreement", agreement},
          {"frames", frames},
          {"explicit_scene", explicit_instancing::to_json(explicit_report)}};
}

ExplicitVsVirtual compare_explicit_and_virtual(const vk::Device& device, const format::Package& package,
                                               render::GpuScene& virtual_scene, const std::vector<gpu::Camera>& cameras,
                                               unsigned rounds, const render::RenderSettings& virtual_settings) {
  if (cameras.empty() || rounds == 0)
    throw std::invalid_argument("compare_explicit_and_virtual: needs at least one camera and one round");
  InstancedScene explicit_scene(device, package);
  InstancedRenderer explicit_renderer(device, explicit_scene);
  render::Renderer virtual_renderer(device, virtual_scene, virtual_settings);
  // Warm-up: pipeline compilation and first-touch of buffers stay out of the medians.
  explicit_renderer.render(cameras.front());
  virtual_renderer.render(cameras.front());
  std::vector<double> explicit_seconds, virtual_seconds;
  std::uint64_t pixels = 0, agree = 0;
  for (unsigned round = 0; round < rounds; ++round)
    for (const gpu::Camera& camera : cameras) {
      // Alternating, so drift of the machine (other jobs, clocks) falls on both alike.
      const InstancedFrame e = explicit_renderer.render(camera);
      const render::Frame v = virtual_renderer.render(camera);
      explicit_seconds.push_back(e.seconds);
      virtual_seconds.push_back(v.seconds);
      if (round == 0) {
        const oracle::CompareResult r = compare_hits(v.hits, e.hits);
        pixels += r.pixels, agree += r.agree;
      }
    }
  ExplicitVsVirtual out;
  out.explicit_seconds_median = bench::frame_stats(explicit_seconds).median;
  out.virtual_seconds_median = bench::frame_stats(virtual_seconds).median;
  out.explicit_report = explicit_scene.report();
  out.explicit_device_bytes = out.explicit_report.memory.total();
  out.virtual_device_bytes = virtual_scene.report().memory.total();
  out.copies = out.explicit_report.copies;
  out.agreement = double(agree) / double(pixels);
  out.frames = explicit_seconds.size();
  return out;
}

}  // namespace nano::explicit_instancing
