#include "runtime/session/session.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "common/error.hpp"
#include "format/validator.hpp"
#include "runtime/vk/embedded_shaders.hpp"

namespace nano::session {

SessionOptions VariantOptions::scene_options() const {
  SessionOptions o;
  o.scene.shell = render::parse_shell_mode(shell, "--shell");
  o.scene.two_level_membranes = levels == "2";
  o.persistent_pipeline_cache = !no_pipeline_cache;
  return o;
}

double parse_lod(const std::string& text) {
  if (text == "off") return 0;
  if (text == "auto") return 1;  // an atom smaller than a pixel: its bead is what a pixel can show
  char* end = nullptr;
  const double pixels = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(pixels > 0 && pixels <= 1e4))
    throw InputError("--lod", "", "expected off, auto or a pixel threshold in (0, 10000], got '" + text + "'");
  return pixels;
}

std::uint64_t parse_flatten(const std::string& text) {
  if (text == "off") return 0;
  if (text == "auto") return render::kFlattenAuto;
  char* end = nullptr;
  const double megabytes = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(megabytes > 0 && megabytes <= 1e6))
    throw InputError("--flatten", "", "expected off, auto or a device-memory budget in MB in (0, 1000000], got '" + text + "'");
  return std::uint64_t(megabytes * 1e6);
}

render::RenderSettings VariantOptions::render_settings() const {
  if (prism != "exact" && prism != "aabb") throw InputError("--prism", "", "expected exact or aabb, got '" + prism + "'");
  if (levels != "3+rep" && levels != "3" && levels != "2")
    throw InputError("--levels", "", "expected 3+rep, 3 or 2, got '" + levels + "'");
  render::RenderSettings s;
  s.precision = render::parse_precision(precision, "--precision");
  s.exact_prism = prism == "exact";
  s.replication_las = levels == "3+rep";
  s.two_level = levels == "2";
  s.lod_pixels = parse_lod(lod);
  s.flatten_bytes = parse_flatten(flatten);
  // Names beyond "medium" are the package's: Renderer and hide_from_oracle resolve them.
  for (const std::string& what : hide) {
    if (what == "medium") s.show_medium = false;
    else s.hidden.push_back(what);
  }
  return s;
}

render::EffectSettings EffectOptions::settings(const format::Package& package) const {
  render::EffectSettings e = no_scene_effects ? render::EffectSettings{} : render::package_effects(package);
  if (!std::isfinite(time)) throw InputError("--time", "", "must be finite");
  e.time = time;
  for (const std::string& plane : clip_planes) e.clipping.planes.push_back(render::parse_clip_plane(plane, "--clip-plane"));
  if (e.clipping.planes.size() > render::kMaxClipPlanes)
    throw InputError("--clip-plane", "", "at most " + std::to_string(render::kMaxClipPlanes) + " planes in all (the scene's included)");
  if (!clip_box.empty()) e.clipping.box = render::parse_clip_box(clip_box, "--clip-box");
  if (!clip_planes.empty() || !clip_box.empty()) e.flag(EffectId::clipping) = true;
  if (!preset.empty()) render::apply_preset(e, preset, "--preset");
  for (const std::string& name : on) render::set_effect(e, name, true, "--effect");
  for (const std::string& name : off) render::set_effect(e, name, false, "--no-effect");
  for (const EffectDeclaration& effect : effect_table())
    for (std::size_t i = 0; i < effect.parameters.size(); ++i) {
      const std::string& text = parameters[static_cast<std::size_t>(effect.id)][i];
      if (text.empty()) continue;
      const EffectParameter& p = effect.parameters[i];
      render::parse_parameter(e.record, p, text, parameter_option(effect, p));
    }
  return e;
}

Camera camera_option(const format::Package& package, const std::string& text) {
  const Camera base = render::package_camera(package);
  if (text.empty()) return base;
  return render::parse_camera(text, base, "--camera");
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point& mark) {
  const auto now = std::chrono::steady_clock::now();
  const double s = std::chrono::duration<double>(now - mark).count();
  mark = now;
  return s;
}

// Opens and validates (a package that fails never reaches the device), timing both steps.
format::Package open_timed(const std::filesystem::path& path, SessionTimings& t) {
  t.mark = std::chrono::steady_clock::now();
  format::Package p = format::Package::open(path);
  t.map = seconds_since(t.mark);
  format::validate_semantics(p);
  t.validate = seconds_since(t.mark);
  return p;
}

// The window case adds `extensions` and a `surface` to present to.
vk::DeviceOptions device_options(const SessionOptions& options, std::vector<std::string> extensions = {},
                                 VkSurfaceKHR surface = VK_NULL_HANDLE) {
  vk::DeviceOptions o;
  o.extensions = std::move(extensions);
  o.present_surface = surface;
  o.persistent_pipeline_cache = options.persistent_pipeline_cache;
  o.shader_hash = vk::embedded_shader_hash();
  return o;
}

void build_scene(RenderSession& s, const render::SceneOptions& options) {
  s.timings.device = seconds_since(s.timings.mark);
  std::fprintf(stderr, "device: %s\n", s.device.description().c_str());
  s.scene = std::make_unique<render::GpuScene>(s.device, s.package, options);
  s.timings.scene = seconds_since(s.timings.mark);
}

}  // namespace

RenderSession::RenderSession(const std::filesystem::path& path, const SessionOptions& options)
    : package(open_timed(path, timings)),
      instance(vk::InstanceOptions{.validation = vk::validation_requested_by_environment()}),
      device(vk::open_ray_query_device(instance, device_options(options))) {
  build_scene(*this, options.scene);
}

RenderSession::RenderSession(const std::filesystem::path& path, const SessionOptions& options,
                             const PresentationOptions& presentation)
    : package(open_timed(path, timings)),
      instance(vk::InstanceOptions{.validation = vk::validation_requested_by_environment(),
                                   .extensions = presentation.instance_extensions}),
      surface(instance.handle(), presentation.create_surface(instance.handle())),
      device(vk::open_ray_query_device(instance, device_options(options, presentation.device_extensions, surface.handle()))) {
  build_scene(*this, options.scene);
}

RenderSession::~RenderSession() { scene.reset(); }  // before the device goes

std::uint64_t RenderSession::validation_errors() const { return instance.validation_errors(); }

}  // namespace nano::session
