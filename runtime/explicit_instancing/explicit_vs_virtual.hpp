#pragma once
// Explicit against virtual instancing on the same device, package and cameras (issue #7 item 5):
// frame time, device memory and whether both show the same atom of the same copy in every pixel.
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "format/package.hpp"
#include "runtime/oracle/render_compare.hpp"
#include "runtime/explicit_instancing/instanced_scene.hpp"
#include "runtime/render/gpu_scene.hpp"
#include "runtime/render/renderer.hpp"
#include "runtime/vk/device.hpp"
#include "shared/camera.h"

namespace nano::explicit_instancing {

// oracle::compare_images of two frames after blanking `reference`'s placement ids (compartment
// instance, element, kind, cell, instance): explicit instancing names a copy only by its number, so
// pixels are judged by (atom, copy number), depth within max(1e-3 Å, 1e-5·t), and bad depths.
// Throws std::invalid_argument for images of different sizes.
oracle::CompareResult compare_hits(std::vector<gpu::PixelHit> reference, const std::vector<gpu::PixelHit>& test);

struct ExplicitVsVirtual {
  double explicit_seconds_median = 0, virtual_seconds_median = 0;  // per frame, wall clock with read-back
  std::uint64_t explicit_device_bytes = 0, virtual_device_bytes = 0;
  std::uint64_t copies = 0;
  double agreement = 0;            // compare_hits over every camera's first-round frames
  InstancedReport explicit_report; // the explicit scene's build: memory by category, seconds
  std::uint64_t frames = 0;        // per renderer, warm-ups excluded
  nlohmann::json to_json() const;
};

// Builds the explicit scene (default InstancedOptions: refuses > 2,000,000 copies with InputError),
// warms both renderers up with one frame each, then renders `cameras` for `rounds` rounds, each
// camera by explicit then virtual instancing, and takes the median frame time of each. Virtual
// memory is virtual_scene.report().memory.total() (sections the device imports in place are not
// counted there; the explicit scene copies its atoms). Throws std::invalid_argument without
// cameras or rounds. `virtual_settings` are the virtual renderer's (effects as given: explicit
// instancing has none, so callers pass them off).
ExplicitVsVirtual compare_explicit_and_virtual(const vk::Device& device, const format::Package& package,
                                               render::GpuScene& virtual_scene, const std::vector<gpu::Camera>& cameras,
                                               unsigned rounds, const render::RenderSettings& virtual_settings = {});

}  // namespace nano::explicit_instancing
