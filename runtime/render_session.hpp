#pragma once
// What `render`, `verify` and `bench` share: a package opened and validated BEFORE any GPU work
// (a package that fails validation never reaches the device), the Vulkan device, the scene on it.
#include <filesystem>
#include <memory>

#include "format/package.hpp"
#include "runtime/render/gpu_scene.hpp"
#include "runtime/vk/device.hpp"
#include "runtime/vk/instance.hpp"

namespace nano::view {

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
