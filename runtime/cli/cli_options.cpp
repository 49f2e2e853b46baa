#include "runtime/cli/cli_options.hpp"

#include <CLI/CLI.hpp>

#include "runtime/session/session.hpp"

namespace nano::cli {

void add_variant_options(CLI::App& command, session::VariantOptions& o) {
  command.add_option("--shell", o.shell, "adaptive-overlap | adaptive | fixed-overlap | fixed")->capture_default_str();
  command.add_option("--prism", o.prism, "exact (ray-prism with bilinear walls) | aabb (the prism's box only)")
      ->capture_default_str();
  command.add_option("--levels", o.levels, "3+rep (µLAS, repLAS, mLAS, nLAS) | 3 (every replication slot queried) | 2 (membrane atoms directly in "
                  "the tile BLASes, placed in tile space: the paper's two-level design)")
      ->capture_default_str();
  command.add_option("--precision", o.precision,
                     "two-float-eye (the eye enters compartment space as a double-computed float pair) | camera-relative "
                     "(float transform of the eye) | world (world-space µLAS, plain float)")
      ->capture_default_str();
  command.add_option("--lod", o.lod,
                     "level of detail: off (every atom) | auto (a copy whose atoms span < 1 pixel shows coarse beads) | PIXELS "
                     "(the threshold)")
      ->capture_default_str();
  command.add_option("--flatten", o.flatten,
                     "flat level: off (every copy traced virtually) | auto (the membrane copies of the triangles nearest the eye "
                     "that fit half the scene's device memory become one TLAS instance each) | MB (that budget)")
      ->capture_default_str();
  command.add_option("--hide", o.hide,
                     "leave out of the picture: medium (the scene's medium, e.g. the plasma between the cells), a compartment "
                     "(every instance of it) or a molecule type, by its name in the scene (compartment:NAME or molecule:NAME "
                     "where both share it); a wrong name lists the package's names; repeatable");
  command.add_flag("--no-pipeline-cache", o.no_pipeline_cache,
                   "neither read nor write the compiled-pipeline cache ($XDG_CACHE_HOME or ~/.cache, folder nanouniverse): "
                   "every run compiles its shaders afresh (for measurements)");
}

void add_effect_options(CLI::App& command, session::EffectOptions& o) {
  command.add_option("--clip-plane", o.clip_planes, "keep points with n·p + d ≥ 0: \"nx,ny,nz,d\" (world Å; repeatable, ≤ 8)");
  command.add_option("--clip-box", o.clip_box, "keep points inside \"x0,y0,z0,x1,y1,z1\" (world Å)");
  command.add_option("--time", o.time, "seconds: proxy animation and jitter are evaluated at this time")->capture_default_str();
  command.add_option("--effect", o.on, "turn an effect on: " + effect_names() + " (repeatable)");
  command.add_option("--no-effect", o.off, "turn an effect off (repeatable)");
  command.add_flag("--no-scene-effects", o.no_scene_effects, "start with every effect off instead of the scene's");
  std::string presets;
  for (const EffectPreset& p : effect_presets()) presets += "; " + std::string(p.name) + ": " + std::string(p.summary);
  command.add_option("--preset", o.preset, "turn on a combination of effects with its parameters (" + preset_names() + presets +
                                               "); --effect, --no-effect and parameter options still apply over it");
  for (const EffectDeclaration& effect : effect_table())
    for (std::size_t i = 0; i < effect.parameters.size(); ++i) {
      const EffectParameter& p = effect.parameters[i];
      command.add_option(parameter_option(effect, p), o.parameters[static_cast<std::size_t>(effect.id)][i],
                         render::parameter_help(effect, p));
    }
}

}  // namespace nano::cli
