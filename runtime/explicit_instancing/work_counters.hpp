#pragma once
// Where the time of a frame goes (`nanoview bench --counters`): the per-pixel work of virtual
// instancing at every level of its traversal beside explicit instancing's on the same views, the
// frame time of each, and what the counters themselves cost (issue #16 item 1).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "format/package.hpp"
#include "runtime/bench/ray_counters.hpp"
#include "runtime/render/gpu_scene.hpp"
#include "runtime/render/renderer.hpp"
#include "runtime/vk/device.hpp"
#include "shared/camera.h"

namespace nano::explicit_instancing {

struct WorkCounters {
  bench::CounterSummary virtual_work;                 // over every pixel of every view
  std::optional<bench::CounterSummary> explicit_work; // none when the scene has too many copies for it
  std::string explicit_skipped;                       // why not
  double agreement = 0;         // compare_hits of the counted frames: virtual against explicit
  bool counting_changes_no_pixel = false;  // virtual hits with counters on == with them off, every view
  // Frame medians measured alternately in one run (virtual without counter code, virtual with the
  // constant off, virtual counting; explicit without and with counting).
  double virtual_no_counter_code_seconds = 0, virtual_seconds = 0, virtual_counting_seconds = 0;
  double explicit_seconds = 0, explicit_counting_seconds = 0;
  std::uint64_t frames = 0;  // per variant, warm-ups excluded
  nlohmann::ordered_json to_json() const;
};

// Builds the explicit scene (beyond 2,000,000 copies, as compare_explicit_and_virtual refuses, the
// explicit side is left out and said why), renders every camera once counting with both
// renderers, then `rounds` rounds of the timed variants in an order that turns each round. Throws
// std::invalid_argument without cameras or rounds. `virtual_settings`: the virtual renderer's
// variant (counters and effect code are set here; callers pass effects off, as explicit instancing).
WorkCounters count_work(const vk::Device& device, const format::Package& package, render::GpuScene& virtual_scene,
                        const std::vector<gpu::Camera>& cameras, unsigned rounds,
                        const render::RenderSettings& virtual_settings = {});

}  // namespace nano::explicit_instancing
