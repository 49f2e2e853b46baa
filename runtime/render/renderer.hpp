#pragma once
// One frame of the ray-query renderer (shaders/render/render.comp): a pinhole camera in, per pixel
// the hit ids, depth and a shaded colour out.
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "runtime/render/gpu_scene.hpp"
#include "runtime/vk/device.hpp"
#include "shared/camera.h"

namespace nano::render {

struct RenderSettings {
  bool exact_prism = true;           // false: a prism's AABB is its only test (bench knob)
  bool replication_las = true;       // false: query every replication slot's mLAS (no repLAS; bench knob)
  bool two_level = false;            // membranes through the scene's atom squares (needs two_level_membranes)
  glm::vec3 light{0.3f, 0.5f, 0.8f}; // direction towards the light (world; normalised here)
  float depth_cue = 0;               // Å over which colour fades towards the background (0: off)
};

struct Frame {
  std::uint32_t width = 0, height = 0;
  std::vector<gpu::PixelHit> hits;   // row-major, row 0 at the top
  std::vector<std::uint32_t> rgba;   // RGBA8 (sRGB), R in the low byte
  double seconds = 0;                // µLAS rebuild + dispatch + read-back, wall clock
};

class Renderer {
public:
  Renderer(const vk::Device& device, GpuScene& scene, const RenderSettings& settings = {});
  ~Renderer();

  // camera.position is the world eye; the µLAS is rebuilt relative to it before tracing.
  Frame render(const gpu::Camera& camera);

  struct Impl;

private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace nano::render
