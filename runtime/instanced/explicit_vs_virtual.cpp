#include "runtime/instanced/explicit_vs_virtual.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "runtime/explicit/render_compare.hpp"
#include "runtime/instanced/instanced_renderer.hpp"
#include "runtime/render/renderer.hpp"

namespace nano::instanced {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

bool is_hit(const gpu::PixelHit& h) { return h.atom != gpu::kNoHit; }

}  // namespace

HitAgreement& HitAgreement::operator+=(const HitAgreement& o) {
  pixels += o.pixels, agree += o.agree, missed += o.missed, different_atom += o.different_atom, depth_only += o.depth_only;
  max_depth_difference = std::max(max_depth_difference, o.max_depth_difference);
  return *this;
}

HitAgreement compare_hits(const std::vector<gpu::PixelHit>& reference, const std::vector<gpu::PixelHit>& test) {
  if (reference.size() != test.size())
    throw std::invalid_argument("compare_hits: images of " + std::to_string(reference.size()) + " and " +
                                std::to_string(test.size()) + " pixels");
  HitAgreement r;
  r.pixels = reference.size();
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const gpu::PixelHit& a = reference[i];
    const gpu::PixelHit& b = test[i];
    if (!is_hit(a) && !is_hit(b)) {
      ++r.agree;
    } else if (is_hit(a) != is_hit(b)) {
      ++r.missed;
    } else if (a.atom != b.atom || a.copy_number_lo != b.copy_number_lo || a.copy_number_hi != b.copy_number_hi) {
      ++r.different_atom;
    } else {
      const double difference = std::abs(double(a.depth) - double(b.depth));  // NaN fails the test below
      if (std::isfinite(difference)) r.max_depth_difference = std::max(r.max_depth_difference, difference);
      if (difference <= oracle::depth_tolerance(a.depth)) ++r.agree;
      else ++r.depth_only;
    }
  }
  return r;
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
          {"explicit_scene", instanced::to_json(explicit_report)}};
}

ExplicitVsVirtual compare_explicit_and_virtual(const vk::Device& device, const format::Package& package,
                                               render::GpuScene& virtual_scene, const std::vector<gpu::Camera>& cameras,
                                               unsigned rounds) {
  if (cameras.empty() || rounds == 0)
    throw std::invalid_argument("compare_explicit_and_virtual: needs at least one camera and one round");
  InstancedScene explicit_scene(device, package);
  InstancedRenderer explicit_renderer(device, explicit_scene);
  render::Renderer virtual_renderer(device, virtual_scene);  // default settings: effects off, as explicit
  // Warm-up: pipeline compilation and first-touch of buffers stay out of the medians.
  explicit_renderer.render(cameras.front());
  virtual_renderer.render(cameras.front());
  std::vector<double> explicit_seconds, virtual_seconds;
  HitAgreement agreement;
  for (unsigned round = 0; round < rounds; ++round)
    for (const gpu::Camera& camera : cameras) {
      // Alternating, so drift of the machine (other jobs, clocks) falls on both alike.
      const InstancedFrame e = explicit_renderer.render(camera);
      const render::Frame v = virtual_renderer.render(camera);
      explicit_seconds.push_back(e.seconds);
      virtual_seconds.push_back(v.seconds);
      if (round == 0) agreement += compare_hits(v.hits, e.hits);
    }
  ExplicitVsVirtual out;
  out.explicit_seconds_median = median(explicit_seconds);
  out.virtual_seconds_median = median(virtual_seconds);
  out.explicit_report = explicit_scene.report();
  out.explicit_device_bytes = out.explicit_report.memory.total();
  out.virtual_device_bytes = virtual_scene.report().memory.total();
  out.copies = out.explicit_report.copies;
  out.agreement = agreement.agreement();
  out.frames = explicit_seconds.size();
  return out;
}

}  // namespace nano::instanced
