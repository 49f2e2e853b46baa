#pragma once
// The runtime session: what the commands (`render`, `verify`, `pick`, `bench`) and the viewer share —
// a package opened and validated BEFORE any GPU work (a package that fails validation never reaches
// the device), the Vulkan device, the scene on it, and the settings the options describe. No
// command-line parsing here: runtime/cli/cli_options.hpp registers these options with CLI11.
#include <array>
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "format/package.hpp"
#include "runtime/render/camera_spec.hpp"
#include "runtime/render/effects.hpp"
#include "runtime/render/gpu_scene.hpp"
#include "runtime/render/renderer.hpp"
#include "runtime/vk/device.hpp"
#include "runtime/vk/instance.hpp"

namespace nano::session {

// What opening a RenderSession takes besides the package: how the scene's acceleration structures
// are built, and whether the device keeps compiled pipelines across runs (vk::DeviceOptions).
struct SessionOptions {
  render::SceneOptions scene;
  bool persistent_pipeline_cache = true;
};

// The variant options `render`, `verify`, `pick`, `bench` and `view` share: --shell, --prism,
// --levels, ..., and --no-pipeline-cache (a choice of how to run, like the others, though not of
// what is drawn).
struct VariantOptions {
  std::string shell = "adaptive-overlap", prism = "exact", levels = "3+rep", precision = "two-float-eye", lod = "off",
              flatten = "auto";
  std::vector<std::string> hide;  // --hide: what the picture leaves out ("medium")
  bool no_pipeline_cache = false;
  // Throw InputError naming the option whose value is not one of its choices. scene_options() is
  // what RenderSession opens the scene (and its device) with.
  SessionOptions scene_options() const;
  render::RenderSettings render_settings() const;
};

// --lod: off → 0; auto → 1 (copies whose atoms span less than a pixel show their beads); a number
// of pixels in (0, 10000]. Throws InputError naming --lod otherwise.
double parse_lod(const std::string& text);

// --flatten: off → 0 (every compartment instance traced virtually); auto → render::kFlattenAuto (the
// flat level may take half the scene's device memory); a number of MB in (0, 1e6]. Throws
// InputError naming --flatten otherwise.
std::uint64_t parse_flatten(const std::string& text);

// The window case (`nanoview view`): the instance also enables `instance_extensions` (the surface
// extensions GLFW names), `create_surface` makes the window's surface from it, and the device must
// present to that surface from its one queue with `device_extensions` (VK_KHR_swapchain) enabled.
struct PresentationOptions {
  std::vector<std::string> instance_extensions, device_extensions;
  std::function<VkSurfaceKHR(VkInstance)> create_surface;
};

// The effect options `render`, `verify`, `pick` and `bench` share. The package's effects are the
// start (unless --no-scene-effects); --effect / --no-effect switch one; clip options turn clipping on;
// parameter options set a value and leave the switch as it is.
struct EffectOptions {
  std::vector<std::string> clip_planes, on, off;
  std::string clip_box;
  double time = 0;
  bool no_scene_effects = false;
  std::string preset;  // --preset: applied over the scene's effects, under the options that follow
  // --<prefix>-<parameter> of every effect of common/effect_table.hpp, as typed; empty: the scene's
  // value (or the table's fallback).
  std::array<std::array<std::string, kMaxEffectParameters>, kEffectCount> parameters;
  // Throws InputError naming the option that does not parse.
  render::EffectSettings settings(const format::Package& package) const;
};

// The camera a command's --camera option names: keys it leaves out (or all, when empty) keep the
// package's camera. Throws InputError naming --camera when the text does not parse.
Camera camera_option(const format::Package& package, const std::string& text);

// Wall-clock seconds of each step of opening a session (bench's load time by stage).
struct SessionTimings {
  double map = 0;       // open and map the file, check the header, table and checksums
  double validate = 0;  // format::validate_semantics
  double device = 0;    // Vulkan instance and device
  double scene = 0;     // GpuScene: uploads and acceleration-structure builds (LoadReport splits it)
  std::chrono::steady_clock::time_point mark;  // end of the previous step
};

struct RenderSession {
  SessionTimings timings;  // first: the members after it are timed as they are built
  format::Package package;
  vk::Instance instance;
  vk::Surface surface;  // presentation sessions only; between instance and device for destruction order
  vk::Device device;
  std::unique_ptr<render::GpuScene> scene;

  // Throws InputError (bad package), DeviceSelectionError (no device with ray queries) or vk errors.
  RenderSession(const std::filesystem::path& path, const SessionOptions& options);
  RenderSession(const std::filesystem::path& path, const SessionOptions& options, const PresentationOptions& presentation);
  ~RenderSession();

  // Validation-layer errors so far (0 without NANO_VALIDATION); commands fail when it is non-zero.
  std::uint64_t validation_errors() const;
};

}  // namespace nano::session
