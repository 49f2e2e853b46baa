// `nanoview bench PKG --effects [--size WxH] [--frames N] [--camera SPEC] [--json out.json]`: what
// each scene effect costs. One run renders the same view with every variant in turn, round after
// round (so drifts of a shared, noisy machine hit all variants alike), and reports the median frame
// time of each as a ratio to "all off" — including the renderer built without any effect code, to
// show that an effect that is off costs nothing.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "runtime/commands.hpp"
#include "runtime/render/camera_spec.hpp"
#include "runtime/render/renderer.hpp"
#include "runtime/render_session.hpp"

namespace nano::view {
namespace {

struct EffectVariant {
  std::string name;
  render::RenderSettings settings;
};

// Every effect on its own, with parameters a user would pick when the scene names none: a cut-away
// plane through the target facing the camera, 8 AO rays of 40 Å, the default light.
std::vector<EffectVariant> effect_variants(const render::RenderSettings& base, const render::EffectSettings& scene,
                                           const render::CameraSpec& camera) {
  render::EffectSettings off;
  off.time = 1.0;
  render::EffectSettings with = scene;
  with.time = 1.0;
  if (!with.clipping.any()) {
    const glm::dvec3 n = glm::normalize(camera.at - camera.eye);  // keep what lies beyond the target
    with.clipping.planes.push_back(glm::dvec4(n, -glm::dot(n, camera.at)));
  }
  if (with.jitter_degrees == 0) with.jitter_degrees = 5, with.jitter_hz = 1;
  if (!scene.ambient_occlusion_on) with.ao_rays = 8, with.ao_radius = 40;
  std::vector<EffectVariant> v;
  const auto add = [&](std::string name, render::EffectSettings e, bool no_code = false) {
    render::RenderSettings s = base;
    s.effects = e;
    s.without_effect_code = no_code;
    v.push_back({std::move(name), s});
  };
  add("no effect code", off, true);
  add("all off", off);
  const auto only = [&](const char* name, bool render::EffectSettings::*flag) {
    render::EffectSettings e = with;
    e.clipping_on = e.animation_on = e.jitter_on = e.ambient_occlusion_on = e.shadows_on = false;
    e.*flag = true;
    add(name, e);
  };
  only("clipping", &render::EffectSettings::clipping_on);
  only("animation", &render::EffectSettings::animation_on);
  only("jitter", &render::EffectSettings::jitter_on);
  only("ao", &render::EffectSettings::ambient_occlusion_on);
  only("shadows", &render::EffectSettings::shadows_on);
  render::EffectSettings all = with;
  all.clipping_on = all.animation_on = all.jitter_on = all.ambient_occlusion_on = all.shadows_on = true;
  add("all on", all);
  return v;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

void add_bench_command(CLI::App& app) {
  struct Options {
    std::string package, size = "256x256", camera, json;
    unsigned frames = 5;
    bool effects = false;
    VariantOptions variant;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("bench", "Measure frame times on this device (--effects: what each scene effect costs)");
  cmd->add_option("PKG", o->package, "package (.nup)")->required();
  cmd->add_flag("--effects", o->effects, "each effect off vs on, and all off vs the renderer without effect code")->required();
  cmd->add_option("--size", o->size, "image size WxH")->capture_default_str();
  cmd->add_option("--frames", o->frames, "measured rounds (each renders every variant once, after one warm-up round)")
      ->check(CLI::Range(1u, 1000u))
      ->capture_default_str();
  cmd->add_option("--camera", o->camera, "\"pos=..;at=..;up=..;fov=..\" (default: the scene's camera)");
  cmd->add_option("--json", o->json, "also write the results as JSON");
  o->variant.add_to(*cmd);
  cmd->callback([o] {
    const auto [w, h] = parse_size(o->size);
    RenderSession session(o->package, o->variant.scene_options());
    render::CameraSpec camera = render::package_camera(session.package);
    try {
      if (!o->camera.empty()) camera = render::parse_camera(o->camera, camera);
    } catch (const std::invalid_argument& e) {
      throw InputError("--camera", "", e.what());
    }
    render::RenderSettings base = o->variant.render_settings();
    base.depth_cue = float(4 * glm::length(camera.at - camera.eye));
    const std::vector<EffectVariant> variants = effect_variants(base, render::package_effects(session.package), camera);
    render::Renderer renderer(session.device, *session.scene, variants.front().settings);
    const gpu::Camera gpu_camera = camera.to_gpu(w, h);
    std::vector<std::vector<double>> seconds(variants.size());
    // Each round starts one variant later, so no variant always follows the costly "all on" frame.
    for (unsigned round = 0; round <= o->frames; ++round)
      for (std::size_t k = 0; k < variants.size(); ++k) {
        const std::size_t v = (k + round) % variants.size();
        renderer.set_settings(variants[v].settings);
        const double s = renderer.render(gpu_camera).seconds;
        if (round > 0) seconds[v].push_back(s);  // round 0 compiles every pipeline
      }
    const double reference = median(seconds[1]);
    nlohmann::ordered_json out;
    out["device"] = session.device.description();
    out["package"] = o->package;
    out["size"] = {w, h};
    out["rounds"] = o->frames;
    out["camera"] = camera.to_string();
    out["reference"] = variants[1].name;
    std::printf("%s, %ux%u, %u rounds, camera %s\n%-16s %12s %12s %14s\n", session.device.description().c_str(), w, h, o->frames,
                camera.to_string().c_str(), "variant", "median s", "vs all off", "rays/frame");
    for (std::size_t v = 0; v < variants.size(); ++v) {
      const double m = median(seconds[v]);
      const std::uint64_t rays = render::Renderer::rays_per_frame(variants[v].settings, std::uint64_t(w) * h);
      std::printf("%-16s %12.4f %12.3f %14llu\n", variants[v].name.c_str(), m, m / reference, (unsigned long long)rays);
      out["variants"].push_back({{"name", variants[v].name},
                                 {"median_seconds", m},
                                 {"min_seconds", *std::min_element(seconds[v].begin(), seconds[v].end())},
                                 {"ratio_to_all_off", m / reference},
                                 {"rays_per_frame_at_most", rays},
                                 {"seconds", seconds[v]}});
    }
    if (!o->json.empty()) {
      const std::string text = out.dump(2) + "\n";
      write_file_atomically(o->json, std::as_bytes(std::span(text.data(), text.size())));
    }
    if (session.validation_errors() != 0)
      throw std::runtime_error("the Vulkan validation layer reported " + std::to_string(session.validation_errors()) + " error(s)");
  });
}

}  // namespace nano::view
