#pragma once
// What `render`, `verify` and `bench` share: a package opened and validated BEFORE any GPU work
// (a package that fails validation never reaches the device), the Vulkan device, the scene on it.
#include <filesystem>
#include <memory>
#include <string>

#include "format/package.hpp"
#include "runtime/render/gpu_scene.hpp"
#include "runtime/render/renderer.hpp"
#include "runtime/vk/device.hpp"
#include "runtime/vk/instance.hpp"

namespace CLI { class App; }

namespace nano::view {

// The variant options `render`, `verify` and `bench` share: --shell, --prism, --levels.
struct VariantOptions {
  std::string shell = "adaptive-overlap", prism = "exact", levels = "3+rep";
  void add_to(CLI::App& command);
  // Throw InputError naming the option whose value is not one of its choices.
  render::SceneOptions scene_options() const;
  render::RenderSettings render_settings() const;
};

struct RenderSession {
  format::Package package;
  vk::Instance instance;
  vk::Device device;
  std::unique_ptr<render::GpuScene> scene;

  // Throws InputError (bad package), DeviceSelectionError (no device with ray queries) or vk errors.
  RenderSession(const std::filesystem::path& path, const render::SceneOptions& options);
  ~RenderSession();

  // Validation-layer errors so far (0 without NANO_VALIDATION); commands fail when it is non-zero.
  std::uint64_t validation_errors() const;
};

}  // namespace nano::view
