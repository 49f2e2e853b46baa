// `nanoview verify PKG [--size WxH] [--cameras N] [--json] [--require F]`: renders views on the
// device and with the CPU oracle (every molecule in view instantiated explicitly with the same
// placement code and ray-traced in double) and reports, pixel by pixel, how far they agree.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "runtime/cli/cli_options.hpp"
#include "common/error.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/oracle/oracle_render.hpp"
#include "runtime/oracle/render_compare.hpp"
#include "runtime/oracle/verify_cameras.hpp"
#include "runtime/render/animation.hpp"
#include "runtime/render/camera_spec.hpp"
#include "runtime/render/image_io.hpp"
#include "runtime/render/renderer.hpp"
#include "runtime/session/oracle_view.hpp"
#include "runtime/session/session.hpp"
#include "runtime/session/view_judge.hpp"

namespace nano::cli {
namespace {

void print_view(const std::string& name, std::uint32_t w, std::uint32_t h, const session::ViewVerdict& v, double gpu_seconds) {
  const oracle::CompareResult& r = v.comparison;
  std::printf("%-24s %4ux%-4u agreement %.5f (%llu pixels hit; missed %llu, other atom %llu, other ids %llu, depth %llu, "
              "bad depth %llu; %llu not explained by radii ±%g or by float placement) gpu %.2f s, oracle %.2f s over %llu atoms\n",
              name.c_str(), w, h, r.agreement(), (unsigned long long)v.reference_hits, (unsigned long long)r.missed,
              (unsigned long long)r.different_atom, (unsigned long long)r.different_ids, (unsigned long long)r.depth_only,
              (unsigned long long)r.bad_depth, (unsigned long long)v.unexplained, session::kRadiusEpsilon, gpu_seconds,
              v.oracle.seconds, (unsigned long long)v.oracle.atoms_last_round);
  for (const auto& m : r.first)
    std::printf("    (%u, %u) %s: oracle %s | gpu %s\n", m.x, m.y, oracle::to_string(m.why),
                oracle::to_json(m.reference).dump().c_str(), oracle::to_json(m.test).dump().c_str());
}

nlohmann::json view_json(const oracle::VerifyCamera& vc, std::uint32_t w, std::uint32_t h, const session::ViewVerdict& v,
                         double gpu_seconds) {
  nlohmann::json view = oracle::to_json(v.comparison);
  view["name"] = vc.name;
  view["camera"] = vc.view.to_string();
  view["size"] = {w, h};
  view["reference_hits"] = v.reference_hits;
  view["unexplained"] = v.unexplained;
  view["gpu_seconds"] = gpu_seconds;
  view["oracle_seconds"] = v.oracle.seconds;
  view["oracle_atoms"] = v.oracle.atoms_last_round;
  return view;
}

void add_to_total(oracle::CompareResult& total, const oracle::CompareResult& r) {
  total.pixels += r.pixels, total.agree += r.agree, total.bad_depth += r.bad_depth, total.missed += r.missed;
  total.different_atom += r.different_atom, total.different_ids += r.different_ids, total.depth_only += r.depth_only;
  total.max_depth_difference = std::max(total.max_depth_difference, r.max_depth_difference);
}

struct VerifyOptions {
  std::string package, size = "96x96";
  session::VariantOptions variant;
  std::size_t cameras = 8;
  bool json = false;
  bool oracle_rays = false;
  double require = 0.999;
  std::uint64_t max_unexplained = 0;
  std::string camera, ids;
  session::EffectOptions effects;
};

void run_verify(const VerifyOptions& o) {
  auto [w, h] = parse_size(o.size);
  if (!o.ids.empty() && o.camera.empty()) throw InputError("--ids", "", "needs --camera: the view the ids file shows");
  render::RenderSettings settings = o.variant.render_settings();
  session::RenderSession session(o.package, o.variant.scene_options());
  settings.effects = o.effects.settings(session.package);
  // The oracle sees what the effects change: moved instances, jittered copies, clipped atoms.
  session::OracleEffects oracle_view = session::oracle_effects(session.package, settings.effects);
  session::hide_from_oracle(session.package, settings, oracle_view.scene);  // --hide hides from both sides
  const oracle::ExplicitScene scene(session.package, oracle_view.scene);
  if (settings.effects.flag(EffectId::ambient_occlusion) || settings.effects.flag(EffectId::shadows))
    std::fprintf(stderr, "verify: ambient occlusion and shadows change colours only; the ids compared here do not see them\n");
  render::Renderer renderer(session.device, *session.scene, settings);
  std::vector<oracle::VerifyCamera> cameras;
  std::vector<gpu::PixelHit> given;
  if (o.camera.empty()) {
    cameras = oracle::verify_cameras(session.package, scene, o.cameras);
  } else {
    cameras.push_back({"--camera", session::camera_option(session.package, o.camera)});
    if (!o.ids.empty()) given = render::read_ids(o.ids, w, h);
  }

  const session::ViewJudge judge(session.package, scene, oracle_view.clip, o.oracle_rays);
  oracle::CompareResult total;
  std::uint64_t total_unexplained = 0;
  nlohmann::json views = nlohmann::json::array();
  for (const oracle::VerifyCamera& vc : cameras) {
    const std::uint32_t cw = vc.odd_size ? (w | 1u) : w, ch = vc.odd_size ? (h | 1u) : h;
    const gpu::Camera camera = vc.view.to_gpu(cw, ch);
    render::Frame frame;
    if (given.empty()) frame = renderer.render(camera);
    else frame.width = w, frame.height = h, frame.hits = given;
    const session::ViewVerdict v = judge.judge(vc.name, camera, frame.hits, cw, ch);
    add_to_total(total, v.comparison);
    total_unexplained += v.unexplained;
    views.push_back(view_json(vc, cw, ch, v, frame.seconds));
    if (!o.json) print_view(vc.name, cw, ch, v, frame.seconds);
  }
  nlohmann::json out{{"agreement", total.agreement()},
                     {"unexplained", total_unexplained},
                     {"radius_epsilon", session::kRadiusEpsilon},
                     {"pixels", total.pixels},
                     {"device", session.device.description()},
                     {"shell", o.variant.shell},
                     {"prism", o.variant.prism},
                     {"levels", o.variant.levels},
                     {"views", views},
                     {"validation_errors", session.validation_errors()}};
  if (o.json) std::printf("%s\n", out.dump(2).c_str());
  else std::printf("agreement %.5f over %llu pixels on %s; %llu differences not explained by radii ±%g or by float placement\n",
                   total.agreement(), (unsigned long long)total.pixels, session.device.description().c_str(),
                   (unsigned long long)total_unexplained, session::kRadiusEpsilon);
  if (session.validation_errors() != 0)
    throw std::runtime_error("the Vulkan validation layer reported " + std::to_string(session.validation_errors()) + " error(s)");
  if (total_unexplained > o.max_unexplained)
    throw std::runtime_error(std::to_string(total_unexplained) + " differing pixels are not explained by a relative radius change of " +
                             std::to_string(session::kRadiusEpsilon) + " (more than --max-unexplained " +
                             std::to_string(o.max_unexplained) + ")");
  if (total.agreement() < o.require)
    throw std::runtime_error("agreement " + std::to_string(total.agreement()) + " is below --require " + std::to_string(o.require));
}

}  // namespace

void add_verify_command(CLI::App& app) {
  auto o = std::make_shared<VerifyOptions>();
  o->variant.flatten = "off";  // verify checks the virtual traversal unless asked for the flat level
  auto* cmd = app.add_subcommand("verify", "Compare the device's image with explicit instancing on the CPU, pixel by pixel");
  cmd->add_option("PKG", o->package, "package (.nup)")->required();
  cmd->add_option("--size", o->size, "image size WxH (cameras that need exactly axis-aligned rays add one to even sizes)")
      ->capture_default_str();
  cmd->add_option("--cameras", o->cameras, "number of views (the hard cases first)")->capture_default_str();
  add_variant_options(*cmd, o->variant);
  cmd->add_option("--require", o->require, "exit 1 when the agreement over all pixels is below this")->capture_default_str();
  cmd->add_option("--max-unexplained", o->max_unexplained,
                  "exit 1 when more differing pixels than this are not explained by changing atom radii by a "
                  "relative 1e-3 (all at once, or each on its own along the pixel's ray): grazing touches and float ties")
      ->capture_default_str();
  cmd->add_flag("--oracle-rays", o->oracle_rays,
                "the oracle traces each pixel's ray alone (no rounds over the view's pyramid): for a whole scene seen "
                "from afar or a cut-away, which the rounds cannot hold");
  cmd->add_flag("--json", o->json, "print JSON (key `agreement`) instead of text");
  cmd->add_option("--camera", o->camera, "one view \"position=..;look_at=..;up=..;fov_degrees=..\" (aliases pos, at, fov) instead of the chosen set (keys left out keep the scene's)");
  cmd->add_option("--ids", o->ids, "judge this ids file (render --ids, a viewer screenshot) instead of rendering; needs --camera");
  add_effect_options(*cmd, o->effects);
  cmd->callback([o] { run_verify(*o); });
}

}  // namespace nano::cli
