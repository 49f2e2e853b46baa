// `nanoview verify PKG [--size WxH] [--cameras N] [--json] [--require F]`: renders views on the
// device and with the CPU oracle (every molecule in view instantiated explicitly with the same
// placement code and ray-traced in double) and reports, pixel by pixel, how far they agree.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "runtime/commands.hpp"
#include "runtime/oracle/oracle_render.hpp"
#include "runtime/oracle/atom_radii_judge.hpp"
#include "runtime/oracle/render_compare.hpp"
#include "runtime/oracle/verify_cameras.hpp"
#include "runtime/render/animation.hpp"
#include "runtime/render/camera_spec.hpp"
#include "runtime/render/image_io.hpp"
#include "runtime/render/renderer.hpp"
#include "runtime/render_session.hpp"

namespace nano::view {
namespace {
// Relative radius change that separates grazing touches and float ties from real differences:
// 1e-3·r is 0.0017 Å on a carbon, far above float error in molecule space yet far below any
// misplaced atom.
constexpr double kRadiusEpsilon = 1e-3;
// Å by which clip planes move to tell float ties at a plane from real clipping errors: the device
// tests atom centres in compartment space in float (~4e-3 Å ulp at 4·10^4 Å).
constexpr double kClipEpsilon = 1e-2;
}  // namespace

void add_verify_command(CLI::App& app) {
  struct Options {
    std::string package, size = "96x96";
    VariantOptions variant;
    std::size_t cameras = 8;
    bool json = false;
    double require = 0.999;
    std::uint64_t max_unexplained = 0;
    std::string camera, ids;
    EffectOptions effects;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("verify", "Compare the device's image with explicit instancing on the CPU, pixel by pixel");
  cmd->add_option("PKG", o->package, "package (.nup)")->required();
  cmd->add_option("--size", o->size, "image size WxH (cameras that need exactly axis-aligned rays add one to even sizes)")
      ->capture_default_str();
  cmd->add_option("--cameras", o->cameras, "number of views (the hard cases first)")->capture_default_str();
  o->variant.add_to(*cmd);
  cmd->add_option("--require", o->require, "exit 1 when the agreement over all pixels is below this")->capture_default_str();
  cmd->add_option("--max-unexplained", o->max_unexplained,
                  "exit 1 when more differing pixels than this are not explained by changing atom radii by a "
                  "relative 1e-3 (all at once, or each on its own along the pixel's ray): grazing touches and float ties")
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "print JSON (key `agreement`) instead of text");
  cmd->add_option("--camera", o->camera, "one view \"pos=..;at=..;up=..;fov=..\" instead of the chosen set (keys left out keep the scene's)");
  cmd->add_option("--ids", o->ids, "judge this ids file (render --ids, a viewer screenshot) instead of rendering; needs --camera");
  o->effects.add_to(*cmd);
  cmd->callback([o] {
    auto [w, h] = parse_size(o->size);
    if (!o->ids.empty() && o->camera.empty()) throw InputError("--ids", "", "needs --camera: the view the ids file shows");
    render::RenderSettings settings = o->variant.render_settings();
    RenderSession session(o->package, o->variant.scene_options());
    settings.effects = o->effects.settings(session.package);
    // The oracle sees what the effects change: moved instances, jittered copies, clipped atoms.
    const OracleEffects oracle_view = oracle_effects(session.package, settings.effects);
    const oracle::ExplicitScene scene(session.package, oracle_view.scene);
    const std::vector<glm::dvec4>& clip = oracle_view.clip;
    if (settings.effects.ambient_occlusion_on || settings.effects.shadows_on)
      std::fprintf(stderr, "verify: ambient occlusion and shadows change colours only; the ids compared here do not see them\n");
    render::Renderer renderer(session.device, *session.scene, settings);
    std::vector<oracle::VerifyCamera> cameras;
    std::vector<gpu::PixelHit> given;
    if (o->camera.empty()) {
      cameras = oracle::verify_cameras(session.package, scene, o->cameras);
    } else {
      const render::CameraSpec spec = camera_option(session.package, o->camera);
      oracle::VerifyCamera vc;
      vc.name = "--camera";
      vc.eye = spec.eye, vc.at = spec.at, vc.up = spec.up, vc.fov_degrees = spec.fov_degrees;
      cameras.push_back(vc);
      if (!o->ids.empty()) given = render::read_ids(o->ids, w, h);
    }

    oracle::CompareResult total;
    std::uint64_t total_unexplained = 0;
    double largest_atom = 0;
    for (const gpu::Atom& a : session.package.records<format::SectionKind::atoms>())
      largest_atom = std::max(largest_atom, double(a.centre_radius.w));
    const double grazing_slack = largest_atom * std::sqrt(2 * kRadiusEpsilon);
    nlohmann::json views = nlohmann::json::array();
    for (const oracle::VerifyCamera& vc : cameras) {
      render::CameraSpec spec;
      spec.eye = vc.eye, spec.at = vc.at, spec.up = vc.up, spec.fov_degrees = vc.fov_degrees;
      const std::uint32_t cw = vc.odd_size ? (w | 1u) : w, ch = vc.odd_size ? (h | 1u) : h;
      const gpu::Camera camera = spec.to_gpu(cw, ch);
      render::Frame frame;
      if (given.empty()) frame = renderer.render(camera);
      else frame.width = w, frame.height = h, frame.hits = given;
      oracle::OracleRenderOptions oracle_options;
      oracle_options.camera_name = vc.name;
      oracle_options.clip = clip;
      oracle::OracleRenderStats stats;
      const std::vector<gpu::PixelHit> reference = oracle::oracle_render(scene, session.package, camera, oracle_options, &stats);
      const oracle::CompareResult r = oracle::compare_images(reference, frame.hits, cw, ch);
      // Which differences a relative change of every radius by ±ε flips: grazing touches and ties.
      std::uint64_t unexplained = 0;
      if (r.agree != r.pixels) {
        oracle::OracleRenderOptions shrink = oracle_options, grow = oracle_options;
        shrink.radius_scale = 1 - kRadiusEpsilon;
        grow.radius_scale = 1 + kRadiusEpsilon;
        const auto shrunk = oracle::oracle_render(scene, session.package, camera, shrink);
        const auto grown = oracle::oracle_render(scene, session.package, camera, grow);
        const oracle::WorldBox bounds = oracle::scene_world_bounds(session.package, &scene);
        // Clip ties: an atom centre within ε of a plane is kept or removed by float rounding; the
        // oracle with every half-space moved by ±ε says which pixels such ties decide.
        std::vector<gpu::PixelHit> clipped_more, clipped_less;
        if (!clip.empty()) {
          oracle::OracleRenderOptions more = oracle_options, less = oracle_options;
          for (glm::dvec4& h : more.clip) h.w -= kClipEpsilon;
          for (glm::dvec4& h : less.clip) h.w += kClipEpsilon;
          clipped_more = oracle::oracle_render(scene, session.package, camera, more);
          clipped_less = oracle::oracle_render(scene, session.package, camera, less);
        }
        for (std::size_t i = 0; i < reference.size(); ++i) {
          if (oracle::classify(reference[i], frame.hits[i]) == oracle::PixelDifference::none ||
              oracle::explained_by_radius_change(frame.hits[i], reference[i], shrunk[i], grown[i], grazing_slack))
            continue;
          if (!clip.empty() && (oracle::classify(clipped_more[i], frame.hits[i]) == oracle::PixelDifference::none ||
                                oracle::classify(clipped_less[i], frame.hits[i]) == oracle::PixelDifference::none))
            continue;
          // Per-atom radii: two grazing touches on one ray, one shrunk and one grown.
          const std::uint32_t x = std::uint32_t(i % cw), y = std::uint32_t(i / cw);
          if (!oracle::explained_by_atom_radii(scene, bounds, glm::dvec3(glm::vec3(camera.position)),
                                               glm::dvec3(gpu::camera_ray_direction(camera, x, y)), frame.hits[i],
                                               kRadiusEpsilon, largest_atom, clip))
            ++unexplained;
        }
      }
      total_unexplained += unexplained;
      std::size_t hit = 0;
      for (const auto& p : reference) hit += p.atom != gpu::kNoHit;
      total.pixels += r.pixels, total.agree += r.agree, total.bad_depth += r.bad_depth, total.missed += r.missed;
      total.different_atom += r.different_atom, total.different_ids += r.different_ids, total.depth_only += r.depth_only;
      total.max_depth_difference = std::max(total.max_depth_difference, r.max_depth_difference);
      nlohmann::json view = oracle::to_json(r);
      view["name"] = vc.name;
      view["camera"] = spec.to_string();
      view["size"] = {cw, ch};
      view["reference_hits"] = hit;
      view["unexplained"] = unexplained;
      view["gpu_seconds"] = frame.seconds;
      view["oracle_seconds"] = stats.seconds;
      view["oracle_atoms"] = stats.atoms_last_round;
      views.push_back(view);
      if (!o->json)
        std::printf("%-24s %4ux%-4u agreement %.5f (%llu pixels hit; missed %llu, other atom %llu, other ids %llu, depth %llu, "
                    "bad depth %llu; %llu not explained by radii ±%g) gpu %.2f s, oracle %.2f s over %llu atoms\n",
                    vc.name.c_str(), cw, ch, r.agreement(), (unsigned long long)hit, (unsigned long long)r.missed,
                    (unsigned long long)r.different_atom, (unsigned long long)r.different_ids,
                    (unsigned long long)r.depth_only, (unsigned long long)r.bad_depth, (unsigned long long)unexplained,
                    kRadiusEpsilon, frame.seconds, stats.seconds,
                    (unsigned long long)stats.atoms_last_round);
      if (!o->json)
        for (const auto& m : r.first)
          std::printf("    (%u, %u) %s: oracle %s | gpu %s\n", m.x, m.y, oracle::to_string(m.why),
                      oracle::to_json(m.reference).dump().c_str(), oracle::to_json(m.test).dump().c_str());
    }
    nlohmann::json out{{"agreement", total.agreement()},
                       {"unexplained", total_unexplained},
                       {"radius_epsilon", kRadiusEpsilon},
                       {"pixels", total.pixels},
                       {"device", session.device.description()},
                       {"shell", o->variant.shell},
                       {"prism", o->variant.prism},
                       {"levels", o->variant.levels},
                       {"views", views},
                       {"validation_errors", session.validation_errors()}};
    if (o->json) std::printf("%s\n", out.dump(2).c_str());
    else std::printf("agreement %.5f over %llu pixels on %s; %llu differences not explained by radii ±%g\n",
                     total.agreement(), (unsigned long long)total.pixels, session.device.description().c_str(),
                     (unsigned long long)total_unexplained, kRadiusEpsilon);
    if (session.validation_errors() != 0)
      throw std::runtime_error("the Vulkan validation layer reported " + std::to_string(session.validation_errors()) + " error(s)");
    if (total_unexplained > o->max_unexplained)
      throw std::runtime_error(std::to_string(total_unexplained) + " differing pixels are not explained by a relative radius change of " +
                               std::to_string(kRadiusEpsilon) + " (more than --max-unexplained " +
                               std::to_string(o->max_unexplained) + ")");
    if (total.agreement() < o->require)
      throw std::runtime_error("agreement " + std::to_string(total.agreement()) + " is below --require " + std::to_string(o->require));
  });
}

}  // namespace nano::view
