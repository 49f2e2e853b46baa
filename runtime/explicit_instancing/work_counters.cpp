#include "runtime/explicit_instancing/work_counters.hpp"

#include <functional>
#include <stdexcept>

#include "common/error.hpp"
#include "runtime/bench/frame_stats.hpp"
#include "runtime/explicit_instancing/explicit_vs_virtual.hpp"
#include "runtime/explicit_instancing/instanced_renderer.hpp"
#include "runtime/render/renderer.hpp"

namespace nano::explicit_instancing {

nlohmann::ordered_json WorkCounters::to_json() const {
  nlohmann::ordered_json out;
  out["virtual"] = bench::to_json(virtual_work);
  if (explicit_work) out["explicit"] = bench::to_json(*explicit_work);
  else out["explicit_skipped"] = explicit_skipped;
  out["agreement_virtual_vs_explicit"] = agreement;
  out["counting_changes_no_pixel"] = counting_changes_no_pixel;
  out["frame_seconds_median"] = {{"virtual_without_counter_code", virtual_no_counter_code_seconds},
                                 {"virtual", virtual_seconds},
                                 {"virtual_counting", virtual_counting_seconds},
                                 {"explicit", explicit_seconds},
                                 {"explicit_counting", explicit_counting_seconds}};
  if (explicit_work) out["virtual_over_explicit"] = virtual_seconds / explicit_seconds;
  out["counters_off_over_no_counter_code"] =
      virtual_no_counter_code_seconds > 0 ? virtual_seconds / virtual_no_counter_code_seconds : 0.0;
  out["frames_per_variant"] = frames;
  return out;
}

WorkCounters count_work(const vk::Device& device, const format::Package& package, render::GpuScene& virtual_scene,
                        const std::vector<gpu::Camera>& cameras, unsigned rounds,
                        const render::RenderSettings& virtual_settings) {
  if (cameras.empty() || rounds == 0) throw std::invalid_argument("count_work: needs at least one camera and one round");
  WorkCounters out;
  std::optional<InstancedScene> explicit_scene;
  std::optional<InstancedRenderer> explicit_renderer;
  try {
    explicit_scene.emplace(device, package);
    explicit_renderer.emplace(device, *explicit_scene);
  } catch (const InputError& e) {
    out.explicit_skipped = e.what();
  }
  render::RenderSettings plain = virtual_settings;
  plain.counters = false;
  plain.without_effect_code = false;
  render::RenderSettings counting = plain;
  counting.counters = true;
  render::RenderSettings no_code = plain;
  no_code.without_effect_code = true;
  render::Renderer virtual_renderer(device, virtual_scene, plain);

  out.counting_changes_no_pixel = true;
  std::vector<std::uint32_t> virtual_words, explicit_words;
  std::uint64_t pixels = 0, agree = 0;
  for (const gpu::Camera& camera : cameras) {
    virtual_renderer.set_settings(plain);
    const render::Frame reference = virtual_renderer.render(camera);
    virtual_renderer.set_settings(counting);
    const render::Frame v = virtual_renderer.render(camera);
    virtual_words.insert(virtual_words.end(), v.counters.begin(), v.counters.end());
    if (explicit_renderer) {
      explicit_renderer->set_counters(true);
      const InstancedFrame e = explicit_renderer->render(camera);
      explicit_words.insert(explicit_words.end(), e.counters.begin(), e.counters.end());
      const oracle::CompareResult r = compare_hits(v.hits, e.hits);
      pixels += r.pixels, agree += r.agree;
    }
    if (oracle::compare_images(reference.hits, v.hits, camera.size.x, camera.size.y, 0).agree != v.hits.size())
      out.counting_changes_no_pixel = false;
  }
  out.virtual_work = bench::summarize_counters(virtual_words);
  if (explicit_renderer) {
    out.explicit_work = bench::summarize_counters(explicit_words);
    out.agreement = double(agree) / double(pixels);
  }

  // Timed variants; every pipeline was compiled above except the one without counter code.
  virtual_renderer.set_settings(no_code);
  virtual_renderer.render(cameras.front());
  const std::function<double(const gpu::Camera&)> variants[] = {
      [&](const gpu::Camera& c) { virtual_renderer.set_settings(no_code); return virtual_renderer.render(c).seconds; },
      [&](const gpu::Camera& c) { virtual_renderer.set_settings(plain); return virtual_renderer.render(c).seconds; },
      [&](const gpu::Camera& c) { virtual_renderer.set_settings(counting); return virtual_renderer.render(c).seconds; },
      [&](const gpu::Camera& c) { explicit_renderer->set_counters(false); return explicit_renderer->render(c).seconds; },
      [&](const gpu::Camera& c) { explicit_renderer->set_counters(true); return explicit_renderer->render(c).seconds; },
  };
  const std::size_t n = explicit_renderer ? std::size(variants) : 3;
  std::vector<double> seconds[std::size(variants)];
  for (unsigned round = 0; round < rounds; ++round)
    for (const gpu::Camera& camera : cameras)
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t v = (k + round) % n;
        seconds[v].push_back(variants[v](camera));
      }
  const auto median = [&](std::size_t v) { return bench::frame_stats(seconds[v]).median; };
  out.virtual_no_counter_code_seconds = median(0);
  out.virtual_seconds = median(1);
  out.virtual_counting_seconds = median(2);
  if (explicit_renderer) {
    out.explicit_seconds = median(3);
    out.explicit_counting_seconds = median(4);
  }
  out.frames = seconds[0].size();
  return out;
}

}  // namespace nano::explicit_instancing
