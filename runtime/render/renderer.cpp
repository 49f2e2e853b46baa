#include "runtime/render/renderer.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <future>
#include <map>
#include <optional>
#include <string>
#include <stdexcept>
#include <tuple>

#include "runtime/placement/visibility.hpp"
#include "runtime/render/animation.hpp"
#include "runtime/render/pixel_outputs.hpp"
#include "runtime/vk/compute_pipeline.hpp"
#include "shared/bindings.h"
#include "shared/render_scene.h"

extern const std::uint32_t nano_spv_render_comp[];
extern const std::size_t nano_spv_render_comp_words;
extern const std::uint32_t nano_spv_render_nano_no_effects_comp[];
extern const std::size_t nano_spv_render_nano_no_effects_comp_words;

namespace nano::render {
namespace {


// What selects a pipeline: the shader build and its specialization constants.
struct Variant {
  bool exact_prism, replication_las, two_level, no_effect_code, eye_from_host, world_space_ulas, counters, lod, flat;
  bool large_areas;  // of the scene, not of the settings: GpuScene::has_large_replication_areas
  bool medium;       // the scene has a medium (GpuScene::has_medium) and the settings show it
  bool hidden_types;  // some molecule type is hidden (RenderSettings::hidden)
  std::array<bool, kEffectCount> effects;  // compiled in, per row of the effect table
  bool code(EffectId id) const { return effects[static_cast<std::size_t>(id)]; }
  bool image_pass() const {
    for (const EffectDeclaration& e : effect_table())
      if (e.image_pass && code(e.id)) return true;
    return false;
  }
  auto key() const {
    return std::tuple(exact_prism, replication_las, two_level, no_effect_code, effects, eye_from_host, world_space_ulas, counters,
                      lod, flat, large_areas, medium, hidden_types);
  }
  bool operator<(const Variant& o) const { return key() < o.key(); }
};

// An effect is compiled in when it is on and has shader code, except where its parameters make it
// do nothing: clipping without a plane or box, jitter of 0°, ambient occlusion of no ray.
bool compiled_in(const EffectSettings& e, const EffectDeclaration& effect) {
  if (!e.flag(effect.id) || effect.spec_constant < 0) return false;
  if (effect.id == EffectId::clipping) return e.clipping.any();
  if (effect.id == EffectId::jitter) return e.jitter_degrees() > 0;
  if (effect.id == EffectId::ambient_occlusion) return e.ao_rays() > 0;
  return true;
}

// `hidden`: what the settings' hidden names resolve to in the scene.
Variant variant_of(const RenderSettings& s, bool large_areas, bool medium, const placement::Visibility& hidden = {}) {
  std::array<bool, kEffectCount> effects{};
  if (!s.without_effect_code)
    for (const EffectDeclaration& effect : effect_table()) effects[static_cast<std::size_t>(effect.id)] = compiled_in(s.effects, effect);
  const bool jitter = effects[static_cast<std::size_t>(EffectId::jitter)];
  return {s.exact_prism, s.replication_las && !s.two_level, s.two_level, s.without_effect_code,
          s.precision == Precision::two_float_eye, s.precision == Precision::world, !s.without_effect_code && s.counters,
          !s.without_effect_code && s.lod_pixels > 0,
          s.flatten_bytes > 0 && !jitter && !s.two_level && s.precision != Precision::world && !hidden.hides_anything(), large_areas,
          medium && s.show_medium, hidden.hides_molecule_types(), effects};
}

std::string name_of(const Variant& v) {
  std::string name;
  const auto add = [&](bool on, const char* what) {
    if (!on) return;
    if (!name.empty()) name += ' ';
    name += what;
  };
  add(v.no_effect_code, "no_effect_code");
  add(v.exact_prism, "exact_prism");
  add(v.replication_las, "replication_las");
  add(v.two_level, "two_level");
  add(v.eye_from_host, "eye_from_host");
  add(v.world_space_ulas, "world_space_ulas");
  add(v.flat, "flat");
  add(!v.large_areas, "small_areas");
  add(v.medium, "medium");
  add(v.hidden_types, "hidden_types");
  for (const EffectDeclaration& effect : effect_table()) add(v.code(effect.id), std::string(effect.name).c_str());
  add(v.counters, "counters");
  add(v.lod, "lod");
  return name;
}

vk::SpirvCode shader_code(const Variant& v) {
  if (v.no_effect_code) return {nano_spv_render_nano_no_effects_comp, nano_spv_render_nano_no_effects_comp_words};
  return {nano_spv_render_comp, nano_spv_render_comp_words};
}

// OpRayQueryProceedKHR instructions in a module (each word of an instruction's first word: count
// << 16 | opcode; the header is 5 words).
unsigned count_ray_query_loops(const vk::SpirvCode& code) {
  constexpr std::uint32_t kOpRayQueryProceedKHR = 4477;
  unsigned loops = 0;
  for (std::size_t at = 5; at < code.word_count;) {
    const std::uint32_t words = code.words[at] >> 16;
    if ((code.words[at] & 0xFFFFu) == kOpRayQueryProceedKHR) ++loops;
    if (words == 0) break;  // malformed: never loop forever
    at += words;
  }
  return loops;
}

vk::ComputePipelineDesc pipeline_desc(const Variant& v) {
  vk::ComputePipelineDesc desc;
  desc.code = shader_code(v);
  desc.sets = {ray_query_set({gpu::NANO_B_ULAS, gpu::NANO_B_FLAT_TLAS, gpu::NANO_B_EXCLUSION_TLAS}, gpu::NANO_RENDER_BINDING_COUNT)};  // set NANO_DESCRIPTOR_SET, the only one
  desc.push_constant_bytes = 2 * sizeof(std::uint32_t);  // the part's first pixel
  desc.specialization.set_bool(gpu::NANO_SPEC_EXACT_PRISM, v.exact_prism);
  desc.specialization.set_bool(gpu::NANO_SPEC_REPLICATION_LAS, v.replication_las);
  desc.specialization.set_bool(gpu::NANO_SPEC_TWO_LEVEL, v.two_level);
  desc.specialization.set_bool(gpu::NANO_SPEC_EYE_FROM_HOST, v.eye_from_host);
  desc.specialization.set_bool(gpu::NANO_SPEC_WORLD_SPACE_ULAS, v.world_space_ulas);
  desc.specialization.set_bool(gpu::NANO_SPEC_FLAT, v.flat);
  desc.specialization.set_bool(gpu::NANO_SPEC_LARGE_REPLICATION_AREAS, v.large_areas);
  desc.specialization.set_bool(gpu::NANO_SPEC_MEDIUM, v.medium);
  desc.specialization.set_bool(gpu::NANO_SPEC_HIDDEN_TYPES, v.hidden_types);
  if (!v.no_effect_code) {
    for (const EffectDeclaration& effect : effect_table())
      if (effect.spec_constant >= 0) desc.specialization.set_bool(effect.spec_constant, v.code(effect.id));
    desc.specialization.set_bool(gpu::NANO_SPEC_COUNTERS, v.counters);
    desc.specialization.set_bool(gpu::NANO_SPEC_LOD, v.lod);
  }
  return desc;
}

// Settings come together from options, the package's scene and the viewer's panel; what the
// renderer knows of their source is the package they are refused for.
void check(const RenderSettings& s, const InputSource& package) {
  const EffectSettings& e = s.effects;
  if (e.flag(EffectId::clipping) && clip_half_spaces(e.clipping).size() > gpu::NANO_MAX_CLIP_HALF_SPACES)
    package.fail("at most 8 clip planes (plus the clip box)");
  if (s.two_level && ((e.flag(EffectId::clipping) && e.clipping.any()) || e.flag(EffectId::jitter)))
    package.fail("--levels 2 (the paper's two-level membrane) has no clipping or jitter; use 3+rep or 3");
  if (e.flag(EffectId::ambient_occlusion) && !(e.ao_rays() >= 1 && e.ao_rays() <= 1024 && e.ao_radius() > 0))
    package.fail("ambient occlusion needs 1 to 1024 rays and a positive radius");
  if (e.flag(EffectId::shadows) && !(glm::length(e.light_direction()) > 0)) package.fail("shadows need a light direction");
  if (s.counters && s.without_effect_code) package.fail("the build without effect code has no counters");
  if (!(s.lod_pixels >= 0 && s.lod_pixels <= 1e4)) package.fail("--lod: a pixel threshold in (0, 10000]");
  if (s.lod_pixels > 0 && s.without_effect_code) package.fail("the build without effect code has no level of detail");
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Pipeline {
  std::chrono::steady_clock::time_point created_from = std::chrono::steady_clock::now();
  vk::ComputePipeline pipeline;
  double create_seconds = seconds_since(created_from);
  double first_dispatch_seconds = -1;
  vk::DescriptorPool pool;
  VkDescriptorSet set;
  Pipeline(const vk::Device& d, const Variant& v) : pipeline(d, pipeline_desc(v)), pool(d, pipeline), set(pool.allocate(pipeline.set_layout(0))) {}
};

// Binds every binding of a pipeline's set to placeholders — one zeroed buffer (its RenderFrame has an
// empty image, so every invocation returns at once) and an empty TLAS — and dispatches one workgroup:
// the pipeline's first dispatch, without the scene.
void warm_up(const vk::Device& device, Pipeline& p) {
  vk::Buffer zeros(device, 64 * 1024, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::HostVisible);
  const std::vector<std::uint32_t> zero_words(16 * 1024, 0u);
  zeros.write(std::as_bytes(std::span(zero_words)));
  // A structure of one box, never traced (no buffer may be empty).
  const VkAabbPositionsKHR box{0, 0, 0, 1, 1, 1};
  const vk::Buffer input =
      vk::Buffer::with_data(device, std::as_bytes(std::span(&box, 1)), vk::kBuildInputUsage, vk::MemoryUse::HostVisible);
  const vk::AccelerationStructure blas = vk::build_bottom_level(device, vk::AabbGeometry{input.address(), 1});
  const VkAccelerationStructureInstanceKHR instance = vk::make_instance(blas, glm::dmat4(1.0), 0);
  const vk::AccelerationStructure tlas = vk::build_top_level(device, std::span(&instance, 1));
  for (const vk::DescriptorBinding& b : p.pipeline.sets().front()) {
    if (b.type == VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR) vk::write_acceleration_structure(device.handle(), p.set, b.binding, tlas);
    else vk::write_storage_buffer(device.handle(), p.set, b.binding, zeros);
  }
  const auto dispatched = std::chrono::steady_clock::now();
  vk::dispatch_region_and_wait(device, p.pipeline, p.set, 0, 0, gpu::NANO_WORKGROUP_SIZE, gpu::NANO_WORKGROUP_SIZE,
                               gpu::NANO_WORKGROUP_SIZE);
  p.first_dispatch_seconds = seconds_since(dispatched);
}

// A pipeline being built on a worker thread (Renderer::prepare).
struct PendingBuild {
  std::future<std::unique_ptr<Pipeline>> pipeline;
  std::chrono::steady_clock::time_point started;
};

}  // namespace

struct Renderer::Impl {
  const vk::Device& device;
  GpuScene& scene;
  RenderSettings settings;
  std::map<Variant, std::unique_ptr<Pipeline>> pipelines;  // built on first use, kept for toggling back
  std::map<Variant, PendingBuild> building;                 // prepare()d, not yet taken into `pipelines`
  vk::Buffer frame_buffer;
  PixelOutputs outputs;
  // The frame begun and not yet finished.
  struct Pending {
    std::uint32_t width = 0, height = 0, next_row = 0, next_column = 0;
    Variant variant{};
    double traced_seconds = 0;  // begin + parts, not the time between them
    gpu::RenderFrame frame{};   // for the image pass, which reads it again with pass.x = 1
  };
  std::optional<Pending> pending;

  Impl(const vk::Device& d, GpuScene& s, const RenderSettings& r) : device(d), scene(s) {
    frame_buffer = vk::Buffer(d, sizeof(gpu::RenderFrame), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::HostVisible);
    set_settings(r);
  }

  // Names resolved for every call with other settings (prepare, ready); a few string compares.
  Variant variant(const RenderSettings& r) const {
    const placement::Visibility hidden = &r == &settings ? visibility : placement::resolve_hidden(scene.package(), r.hidden);
    return variant_of(r, scene.has_large_replication_areas(), scene.has_medium(), hidden);
  }
  placement::Visibility visibility;  // settings.hidden resolved

  void set_settings(const RenderSettings& r) {
    const InputSource package(scene.package().name());
    check(r, package);
    if (r.lod_pixels > 0 && !scene.has_beads())
      package.fail("no beads (baked before format 2.5), so no level of detail: bake it again, or --lod off");
    visibility = placement::resolve_hidden(scene.package(), r.hidden);
    settings = r;
    const Variant v = variant(settings);
    if (const auto b = building.find(v); b != building.end()) {
      std::future<std::unique_ptr<Pipeline>> pending = std::move(b->second.pipeline);
      building.erase(b);
      pipelines.emplace(v, pending.get());  // waits; rethrows the worker's error (a later call builds it here)
    }
    if (!pipelines.count(v)) pipelines.emplace(v, std::make_unique<Pipeline>(device, v));
  }

  void prepare(const RenderSettings& r) {
    check(r, scene.package().name());
    const Variant v = variant(r);
    if (pipelines.count(v) || building.count(v)) return;
    const vk::Device& d = device;
    building.emplace(v, PendingBuild{std::async(std::launch::async,
                                                [&d, v] {
                                                  auto p = std::make_unique<Pipeline>(d, v);
                                                  warm_up(d, *p);
                                                  return p;
                                                }),
                                     std::chrono::steady_clock::now()});
  }

  bool ready(const RenderSettings& r) {
    const Variant v = variant(r);
    if (pipelines.count(v)) return true;
    const auto b = building.find(v);
    if (b == building.end() || b->second.pipeline.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return false;
    std::future<std::unique_ptr<Pipeline>> done = std::move(b->second.pipeline);
    building.erase(b);
    pipelines.emplace(v, done.get());  // rethrows the worker's error
    return true;
  }

  gpu::RenderFrame frame_record(const gpu::Camera& camera) const {
    const EffectSettings& e = settings.effects;
    gpu::RenderFrame frame{};
    frame.camera = camera;
    frame.levels = glm::uvec4(scene.first_square_level(), scene.first_cube_level(), scene.molecule_type_count(),
                              scene.first_atom_square_level());
    const glm::vec3 light = e.flag(EffectId::shadows) ? glm::vec3(e.light_direction()) : settings.light;
    frame.light = glm::vec4(glm::normalize(light), 4 * settings.focus_distance);
    if (e.flag(EffectId::clipping)) {
      // In the µLAS's frame: camera-relative, n·(x' + eye) + d = n·x' + (d + n·eye), in double.
      const glm::dvec3 eye = ulas_origin(camera);
      const std::vector<glm::dvec4> half_spaces = clip_half_spaces(e.clipping);
      for (std::size_t k = 0; k < half_spaces.size(); ++k)
        frame.clip[k] = glm::vec4(glm::vec3(half_spaces[k]), float(half_spaces[k].w + glm::dot(glm::dvec3(half_spaces[k]), eye)));
      frame.effects.x = std::uint32_t(half_spaces.size());
    }
    frame.effects.y = e.ao_rays();
    frame.effects.z = e.sample_index;
    frame.effects.w = scene.first_bead_level();
    frame.flat_eye = variant(settings).flat ? scene.flat_eye(ulas_origin(camera)) : glm::vec4(0.f);
    frame.lod = glm::vec4(2.0f * camera.forward.w / float(camera.size.y), float(settings.lod_pixels), gpu::NANO_TYPICAL_ATOM_DIAMETER, 0.f);
    const glm::vec3 jitter = jitter_frame_parameters(e);
    frame.effect_parameters = glm::vec4(e.ao_radius(), jitter.x, jitter.y, jitter.z);
    frame.effect_record = effect_record(e);
    return frame;
  }

  std::uint64_t flatten_budget() const {
    if (!variant(settings).flat) return 0;
    if (settings.flatten_bytes != kFlattenAuto) return settings.flatten_bytes;
    const MemoryReport& m = scene.report().memory;
    return (m.total() - m.flat) / 2;
  }

  // Where the µLAS's origin lies in the world: the eye, or the world origin (Precision::world).
  glm::dvec3 ulas_origin(const gpu::Camera& camera) const {
    return settings.precision == Precision::world ? glm::dvec3(0.0) : glm::dvec3(glm::vec3(camera.position));
  }

  Frame render(const gpu::Camera& camera) {
    begin(camera);
    while (!trace_part(std::uint64_t(camera.size.x) * camera.size.y).complete) {
    }
    return finish();
  }

  void begin(const gpu::Camera& camera) {
    const std::uint32_t w = camera.size.x, h = camera.size.y;
    if (w == 0 || h == 0) throw std::invalid_argument("render: image size must be positive");
    pending.reset();
    const auto start = std::chrono::steady_clock::now();
    const glm::dvec3 eye = ulas_origin(camera);
    scene.set_visibility(visibility);
    scene.set_flatten(flatten_budget(), camera, variant(settings).code(EffectId::clipping), settings.flatten_new_copies);
    if (settings.effects.flag(EffectId::animation)) {
      const std::vector<format::InstanceTransform> moved = animated_instance_transforms(scene.package(), settings.effects.time);
      scene.set_eye(eye, moved);
    } else {
      scene.set_eye(eye);
    }
    const gpu::RenderFrame frame = frame_record(camera);
    frame_buffer.write(std::as_bytes(std::span(&frame, 1)));
    const Variant v = variant(settings);
    Pipeline& p = *pipelines.at(v);
    scene.write_descriptors(p.set);
    vk::write_storage_buffer(device.handle(), p.set, gpu::NANO_B_FRAME, frame_buffer);
    outputs.bind(device, p.set, {gpu::NANO_B_HITS, gpu::NANO_B_COLOURS, gpu::NANO_B_COUNTERS}, std::uint64_t(w) * h, v.counters);
    pending = Pending{w, h, 0, 0, v, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), frame};
  }

  Renderer::Part trace_part(std::uint64_t pixels) {
    if (!pending) throw std::logic_error("Renderer::trace_part: no frame begun");
    if (variant(settings).key() != pending->variant.key())
      throw std::logic_error("Renderer::trace_part: the settings changed since begin()");
    Pending& f = *pending;
    if (f.next_row >= f.height) throw std::logic_error("Renderer::trace_part: the frame is complete; finish() it");
    const auto start = std::chrono::steady_clock::now();
    const std::uint64_t wg = gpu::NANO_WORKGROUP_SIZE;
    const std::uint64_t strip_pixels = wg * f.width;
    std::uint32_t x = f.next_column, y = f.next_row, w, h;
    if (f.next_column == 0 && pixels >= std::uint64_t(f.width) * (f.height - f.next_row)) {  // the rest
      h = f.height - f.next_row;
      w = f.width;
      f.next_row = f.height;
    } else if (f.next_column == 0 && pixels >= strip_pixels) {  // whole strips of 8 rows
      h = std::uint32_t(std::min<std::uint64_t>(pixels / strip_pixels * wg, f.height - f.next_row));
      w = f.width;
      f.next_row += h;
    } else {  // a run of workgroups along the current strip
      w = std::uint32_t(std::clamp<std::uint64_t>(pixels / (wg * wg) * wg, wg, f.width - f.next_column));
      h = std::uint32_t(std::min<std::uint64_t>(wg, f.height - f.next_row));
      f.next_column += w;
      if (f.next_column >= f.width) f.next_column = 0, f.next_row += h;
    }
    Pipeline& p = *pipelines.at(f.variant);
    const auto dispatched = std::chrono::steady_clock::now();
    vk::dispatch_region_and_wait(device, p.pipeline, p.set, x, y, w, h, std::uint32_t(wg));
    if (p.first_dispatch_seconds < 0) p.first_dispatch_seconds = seconds_since(dispatched);
    if (f.next_row >= f.height && f.variant.image_pass()) image_pass(p, f);
    f.traced_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return {std::uint64_t(w) * h, f.next_row >= f.height};
  }

  // Effects that need the finished hits of their neighbours (outlines) run once the last part is
  // traced: the same pipeline over the whole image, told by the frame record that it is that pass.
  void image_pass(Pipeline& p, Pending& f) {
    gpu::RenderFrame frame = f.frame;
    frame.pass = glm::uvec4(1u, 0u, 0u, 0u);
    frame_buffer.write(std::as_bytes(std::span(&frame, 1)));
    vk::dispatch_region_and_wait(device, p.pipeline, p.set, 0, 0, f.width, f.height, std::uint32_t(gpu::NANO_WORKGROUP_SIZE));
  }

  Frame finish() {
    if (!pending || pending->next_row < pending->height) throw std::logic_error("Renderer::finish: the frame is not complete");
    const auto start = std::chrono::steady_clock::now();
    Frame out;
    out.width = pending->width, out.height = pending->height;
    outputs.read(out.hits, out.rgba, out.counters);
    out.seconds = pending->traced_seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    pending.reset();
    return out;
  }
};

Precision parse_precision(std::string_view text, const InputSource& source) {
  if (text == "two-float-eye") return Precision::two_float_eye;
  if (text == "camera-relative") return Precision::camera_relative;
  if (text == "world") return Precision::world;
  source.fail("expected two-float-eye, camera-relative or world, got '" + std::string(text) + "'");
}

const char* to_string(Precision precision) {
  switch (precision) {
    case Precision::two_float_eye: return "two-float-eye";
    case Precision::camera_relative: return "camera-relative";
    case Precision::world: return "world";
  }
  return "?";
}

Renderer::Renderer(const vk::Device& device, GpuScene& scene, const RenderSettings& settings)
    : impl_(std::make_unique<Impl>(device, scene, settings)) {}
Renderer::~Renderer() = default;
Frame Renderer::render(const gpu::Camera& camera) { return impl_->render(camera); }
void Renderer::begin(const gpu::Camera& camera) { impl_->begin(camera); }
Renderer::Part Renderer::trace_part(std::uint64_t pixels) { return impl_->trace_part(pixels); }
Frame Renderer::finish() { return impl_->finish(); }
void Renderer::set_settings(const RenderSettings& settings) { impl_->set_settings(settings); }
void Renderer::prepare(const RenderSettings& settings) { impl_->prepare(settings); }
bool Renderer::ready(const RenderSettings& settings) { return impl_->ready(settings); }
double Renderer::preparing_seconds(const RenderSettings& settings) const {
  const auto b = impl_->building.find(impl_->variant(settings));
  return b == impl_->building.end() ? 0.0 : seconds_since(b->second.started);
}
const RenderSettings& Renderer::settings() const { return impl_->settings; }

Renderer::PipelineBuild Renderer::pipeline_build() const {
  const Variant v = impl_->variant(impl_->settings);
  const Pipeline& p = *impl_->pipelines.at(v);
  const vk::SpirvCode code = shader_code(v);
  return {name_of(v), code.word_count * sizeof(std::uint32_t), count_ray_query_loops(code), p.create_seconds, p.first_dispatch_seconds};
}

bool shown(const RenderSettings& settings, const std::string& name) {
  if (name == "medium") return settings.show_medium;
  return std::find(settings.hidden.begin(), settings.hidden.end(), name) == settings.hidden.end();
}

void set_shown(RenderSettings& settings, const std::string& name, bool show) {
  if (name == "medium") {
    settings.show_medium = show;
    return;
  }
  std::erase(settings.hidden, name);
  if (!show) settings.hidden.push_back(name);
}

// The settings' part of the name: the scene's part (small_areas) shows in pipeline_build().
std::string Renderer::variant_name(const RenderSettings& settings) { return name_of(variant_of(settings, true, false)); }

std::uint64_t Renderer::rays_per_frame(const RenderSettings& settings, std::uint64_t pixels) {
  const Variant v = variant_of(settings, true, false);
  return pixels * (1 + (v.code(EffectId::shadows) ? 1 : 0) + (v.code(EffectId::ambient_occlusion) ? settings.effects.ao_rays() : 0));
}

}  // namespace nano::render
