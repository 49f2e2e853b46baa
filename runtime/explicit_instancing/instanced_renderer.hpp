#pragma once
// One frame of explicit instancing (shaders/explicit_instancing/instanced.comp): a pinhole camera in, per pixel
// the hit atom, copy number, depth and a shaded colour out — the fields render::Renderer's frames
// carry that explicit instancing knows; the copy's placement ids (compartment instance, element,
// kind, cell, instance) stay kNoHit / −1.
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "runtime/explicit_instancing/instanced_scene.hpp"
#include "runtime/vk/device.hpp"
#include "shared/camera.h"

namespace nano::explicit_instancing {

struct InstancedFrame {
  std::uint32_t width = 0, height = 0;
  std::vector<gpu::PixelHit> hits;  // row-major, row 0 at the top
  std::vector<std::uint32_t> rgba;  // RGBA8 (sRGB), R in the low byte
  std::vector<std::uint32_t> counters;  // with counters on: NANO_RAY_COUNTER_COUNT words a pixel
  double seconds = 0;               // TLAS preparation (a rebuild only when eye_relative) + dispatch + read-back
};

class InstancedRenderer {
public:
  // `light`: direction towards the light (world; normalised here), as render::RenderSettings::light.
  InstancedRenderer(const vk::Device& device, InstancedScene& scene, const glm::vec3& light = {0.3f, 0.5f, 0.8f});
  ~InstancedRenderer();

  // Throws std::invalid_argument for an empty image.
  InstancedFrame render(const gpu::Camera& camera);

  // Count the work per pixel in the next frames (a second pipeline, built on first use).
  void set_counters(bool on);

  struct Impl;

private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace nano::explicit_instancing
