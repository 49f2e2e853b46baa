#include "runtime/render_session.hpp"

#include <cstdio>

#include <CLI/CLI.hpp>

#include "common/error.hpp"
#include "format/validator.hpp"

namespace nano::view {

void VariantOptions::add_to(CLI::App& command) {
  command.add_option("--shell", shell, "adaptive-overlap | adaptive | fixed-overlap | fixed")->capture_default_str();
  command.add_option("--prism", prism, "exact (ray-prism with bilinear walls) | aabb (the prism's box only)")
      ->capture_default_str();
  command.add_option("--levels", levels, "3+rep (µLAS, repLAS, mLAS, nLAS) | 3 (every replication slot queried) | 2 (membrane atoms directly in "
                  "the tile BLASes, placed in tile space: the paper's two-level design)")
      ->capture_default_str();
}

render::SceneOptions VariantOptions::scene_options() const {
  render::SceneOptions o;
  try {
    o.shell = render::parse_shell_mode(shell);
  } catch (const std::invalid_argument& e) {
    throw InputError("--shell", "", e.what());
  }
  o.two_level_membranes = levels == "2";
  return o;
}

render::RenderSettings VariantOptions::render_settings() const {
  if (prism != "exact" && prism != "aabb") throw InputError("--prism", "", "expected exact or aabb, got '" + prism + "'");
  if (levels != "3+rep" && levels != "3" && levels != "2")
    throw InputError("--levels", "", "expected 3+rep, 3 or 2, got '" + levels + "'");
  render::RenderSettings s;
  s.exact_prism = prism == "exact";
  s.replication_las = levels == "3+rep";
  s.two_level = levels == "2";
  return s;
}

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
