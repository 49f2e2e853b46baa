// `nanoview pick PKG --camera SPEC --size WxH X Y [X Y ...] [--oracle] [--shell …] [effect options]`: what each
// pixel (X, Y) of a view shows, one line of JSON a pixel in the order given (render::describe_hit plus "x", "y"),
// from one frame of the device or, with --oracle, one image of the CPU explicit-instancing oracle: the two
// must name the same atom. Many pixels cost one start of the renderer, not one each.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "runtime/cli/cli_options.hpp"
#include "common/error.hpp"
#include "format/validator.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/oracle/oracle_render.hpp"
#include "runtime/render/animation.hpp"
#include "runtime/render/camera_spec.hpp"
#include "runtime/render/effects.hpp"
#include "runtime/render/pick_info.hpp"
#include "runtime/render/renderer.hpp"
#include "runtime/session/oracle_view.hpp"
#include "runtime/session/session.hpp"

namespace nano::cli {

void add_pick_command(CLI::App& app) {
  struct Options {
    std::string package, size = "384x384", camera;
    std::vector<std::uint32_t> pixels;  // x, y pairs
    bool oracle = false;
    session::VariantOptions variant;
    session::EffectOptions effects;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("pick", "Name the atom, molecule, compartment and copy pixels of a view show (a line of JSON each)");
  cmd->add_option("PKG", o->package, "package (.nup)")->required();
  cmd->add_option("X Y", o->pixels, "pixel column (0 = left) and row (0 = top); more pairs pick more pixels of the same view")
      ->required()->expected(2, -1);
  cmd->add_option("--size", o->size, "image size WxH")->capture_default_str();
  cmd->add_option("--camera", o->camera,
                  "\"position=x,y,z;look_at=x,y,z;up=x,y,z;fov_degrees=DEG\" (world Å, vertical; aliases pos, at, fov); keys left out keep the scene's camera");
  cmd->add_flag("--oracle", o->oracle,
                "trace the pixel with the CPU oracle (explicit instancing, no device needed) instead of the GPU; "
                "the variant options then do not apply, the effect options do");
  add_variant_options(*cmd, o->variant);
  add_effect_options(*cmd, o->effects);
  cmd->callback([o] {
    const auto [w, h] = parse_size(o->size);
    if (o->pixels.size() % 2 != 0)
      throw InputError("X Y", "", std::to_string(o->pixels.size()) + " numbers do not make (X, Y) pairs");
    std::vector<std::uint32_t> pixels;
    for (std::size_t i = 0; i < o->pixels.size(); i += 2) {
      const std::uint32_t x = o->pixels[i], y = o->pixels[i + 1];
      if (x >= w || y >= h)
        throw InputError("X Y", "", "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") lies outside the " +
                                        o->size + " image");
      pixels.push_back(y * w + x);
    }
    std::vector<nlohmann::json> out;
    if (o->oracle) {
      // The oracle needs no device: open the package as RenderSession would, without Vulkan.
      const format::Package package = format::open_validated(o->package);
      // What the effects change for ids, as verify gives them to the oracle: moved instances,
      // jittered copies, clipped atoms (AO and shadows change colours only).
      const render::EffectSettings effects = o->effects.settings(package);
      session::OracleEffects oracle_view = session::oracle_effects(package, effects);
      session::hide_from_oracle(package, o->variant.render_settings(), oracle_view.scene);
      const oracle::ExplicitScene scene(package, oracle_view.scene);
      oracle::OracleRenderOptions render_options;
      render_options.clip = oracle_view.clip;
      render_options.only_pixels = pixels;
      const gpu::Camera camera = session::camera_option(package, o->camera).to_gpu(w, h);
      const std::vector<gpu::PixelHit> hits = oracle::oracle_render(scene, package, camera, render_options);
      for (const std::uint32_t pixel : pixels) out.push_back(render::describe_hit(package, hits[pixel]));
    } else {
      render::RenderSettings settings = o->variant.render_settings();
      session::RenderSession session(o->package, o->variant.scene_options());
      settings.effects = o->effects.settings(session.package);
      render::Renderer renderer(session.device, *session.scene, settings);
      const render::Frame frame = renderer.render(session::camera_option(session.package, o->camera).to_gpu(w, h));
      for (const std::uint32_t pixel : pixels) out.push_back(render::describe_hit(session.package, frame.hits[pixel]));
      if (session.validation_errors() != 0)
        throw std::runtime_error("the Vulkan validation layer reported " + std::to_string(session.validation_errors()) + " error(s)");
    }
    for (std::size_t i = 0; i < out.size(); ++i) {
      out[i]["x"] = o->pixels[2 * i];
      out[i]["y"] = o->pixels[2 * i + 1];
      std::printf("%s\n", out[i].dump(-1, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
    }
  });
}

}  // namespace nano::cli
