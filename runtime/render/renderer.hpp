#pragma once
// One frame of the ray-query renderer (shaders/render/render.comp): a pinhole camera in, per pixel
// the hit ids, depth and a shaded colour out.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "runtime/render/effects.hpp"
#include "runtime/render/gpu_scene.hpp"
#include "runtime/vk/device.hpp"
#include "shared/camera.h"

namespace nano::render {

// Where the primary ray's precision comes from (bench knob; README "Knobs").
enum class Precision {
  two_float_eye,    // µLAS relative to the eye and the compartment-space eye as a double-computed float pair
  camera_relative,  // µLAS relative to the eye; the eye enters compartment space by the float transform
  world,            // µLAS in world coordinates, rays from the world eye: plain float everywhere
};
// Throws an InputError against `source` naming the choices.
Precision parse_precision(std::string_view text, const InputSource& source);
const char* to_string(Precision precision);

struct RenderSettings {
  bool exact_prism = true;           // false: a prism's AABB is its only test (bench knob)
  bool replication_las = true;       // false: query every replication slot's mLAS (no repLAS; bench knob)
  bool two_level = false;            // membranes through the scene's atom squares (needs two_level_membranes)
  Precision precision = Precision::two_float_eye;
  glm::vec3 light{0.3f, 0.5f, 0.8f}; // direction towards the light (world; normalised here)
  // Å from the eye to what it looks at: colour fades towards the background over four times it (the
  // built-in depth cue). 0: no depth cue.
  float focus_distance = 0;
  EffectSettings effects;            // all off by default; render::package_effects gives the scene's
  bool without_effect_code = false;  // the shader built without any effect or counter code (bench: what "off" costs)
  bool counters = false;             // count the work per pixel (Frame::counters; bench --counters)
  double lod_pixels = 0;             // > 0: copies whose atoms span fewer pixels are drawn as beads (--lod)
  // Device memory for the flat level (GpuScene::set_flatten_budget, --flatten): 0 traces every
  // compartment instance virtually; kFlattenAuto: half of what the scene itself takes. No flat
  // level with jitter, --levels 2 or Precision::world (those measure or move the virtual path).
  std::uint64_t flatten_bytes = 0;
  // Copies the flat level may enumerate on the CPU before a frame (the rest before later frames):
  // the viewer bounds the pause a frame's start takes; a single render takes them all.
  std::uint64_t flatten_new_copies = ~std::uint64_t{0};
  // Trace the scene's medium (its plasma) when it has one; false shows the cells alone, and the
  // pipeline then has no medium code at all (--hide medium).
  bool show_medium = true;
  // Compartments and molecule types left out of the picture, by name (--hide; placement/visibility.hpp
  // resolves them against the package and says which names it has). A hidden compartment's instances
  // are masked out of the µLAS (no shader cost); hiding a molecule type compiles a variant that drops
  // its candidates; either turns the flat level off.
  std::vector<std::string> hidden;
};
// Whether `name` ("medium", or a name RenderSettings::hidden takes) is in the picture, and switching
// it (the viewer's panel and script).
bool shown(const RenderSettings& settings, const std::string& name);
void set_shown(RenderSettings& settings, const std::string& name, bool shown);
inline constexpr std::uint64_t kFlattenAuto = ~std::uint64_t{0};

struct Frame {
  std::uint32_t width = 0, height = 0;
  std::vector<gpu::PixelHit> hits;   // row-major, row 0 at the top
  std::vector<std::uint32_t> rgba;   // RGBA8 (sRGB), R in the low byte
  std::vector<std::uint32_t> counters;  // with RenderSettings::counters: NANO_RAY_COUNTER_COUNT words a pixel
  double seconds = 0;                // µLAS rebuild + dispatch + read-back, wall clock
};

class Renderer {
public:
  Renderer(const vk::Device& device, GpuScene& scene, const RenderSettings& settings = {});
  ~Renderer();

  // camera.position is the world eye; the µLAS is rebuilt relative to it before tracing.
  Frame render(const gpu::Camera& camera);

  // The same frame in parts, so a caller can do other work (a viewer: input, presenting) between
  // them: begin() prepares it, each trace_part() traces about `pixels` more (whole 8×8 workgroups:
  // runs along strips of 8 rows, or whole strips when the budget allows) and says how many it
  // traced and whether the frame is complete, finish() reads it back. A new begin() abandons an
  // unfinished frame; settings must not change in between (std::logic_error).
  struct Part {
    std::uint64_t pixels = 0;
    bool complete = false;
  };
  void begin(const gpu::Camera& camera);
  Part trace_part(std::uint64_t pixels);
  Frame finish();

  // Builds the pipeline `settings` select on a worker thread — vkCreateComputePipelines, then one
  // dispatch of one workgroup on placeholder resources, where a driver that compiles at first use
  // (lavapipe: LLVM) compiles — unless it is built or being built; returns at once. Throws
  // InputError for settings set_settings would refuse. ready() says when it is done;
  // set_settings() with them waits for it. A viewer switching an effect keeps showing what it has
  // meanwhile instead of stalling.
  void prepare(const RenderSettings& settings);
  bool ready(const RenderSettings& settings);
  double preparing_seconds(const RenderSettings& settings) const;  // since prepare(); 0 when not being built

  // Effects and knobs for the next frames. A change of what is compiled in (the specialization
  // constants) builds another pipeline, once; parameters (planes, time, AO radius) cost nothing.
  // Throws an InputError naming the package for more than 8 clip planes, effects the two-level path
  // lacks or a level of detail without beads.
  void set_settings(const RenderSettings& settings);
  const RenderSettings& settings() const;

  // What the pipeline of the current settings cost to build (bench --compile): vkCreateComputePipelines
  // and its first dispatch, where a driver that compiles lazily does its work (lavapipe: LLVM).
  struct PipelineBuild {
    std::string variant;                 // the shader build and specialization constants that select it
    std::size_t spirv_bytes = 0;         // the SPIR-V module
    unsigned ray_query_loops = 0;        // OpRayQueryProceedKHR in the module: each is a whole traversal once compiled
    double create_seconds = 0;
    double first_dispatch_seconds = -1;  // < 0: not dispatched yet
  };
  PipelineBuild pipeline_build() const;
  // "exact_prism replication_las ..." — the specialization constants `settings` turn on (and
  // "no_effect_code" for the build without effect code); equal names, one pipeline.
  static std::string variant_name(const RenderSettings& settings);

  // Rays one frame of `pixels` pixels traces with these settings (primary + shadow + AO).
  static std::uint64_t rays_per_frame(const RenderSettings& settings, std::uint64_t pixels);

  struct Impl;

private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace nano::render
