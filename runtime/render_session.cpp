#include "runtime/render_session.hpp"

#include <cstdio>

#include "format/validator.hpp"

namespace nano::view {

RenderSession::RenderSession(const std::filesystem::path& path, const render::SceneOptions& options)
    : package(format::open_validated(path)),
      instance(vk::InstanceOptions{.validation = vk::validation_requested_by_environment()}),
      device(vk::open_ray_query_device(instance)) {
  std::fprintf(stderr, "device: %s\n", device.description().c_str());
  scene = std::make_unique<render::GpuScene>(device, package, options);
}

RenderSession::~RenderSession() { scene.reset(); }  // before the device goes

std::uint64_t RenderSession::validation_errors() const { return instance.validation_errors(); }

}  // namespace nano::view
