// `nanoview view PKG [--script FILE] [--size WxH] [--camera SPEC] [--path FILE] [effect and variant
// options]`: the interactive viewer (runtime/viewer/), or a scripted run of it for tests and figures.
#include <memory>
#include <string>

#include "runtime/cli/cli_options.hpp"
#include "common/error.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/viewer/script.hpp"
#include "runtime/viewer/viewer_app.hpp"

namespace nano::cli {

void add_view_command(CLI::App& app) {
  struct Options {
    viewer::ViewerOptions viewer;
    std::string size;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "view", "Interactive viewer (orbit/fly cameras, effects, picking, screenshots); --script runs commands instead");
  cmd->add_option("PKG", o->viewer.package, "package (.nup)")->required();
  cmd->add_option("--script", o->viewer.script,
                  "run the commands of FILE (camera, clip, effect, time, wait, pick, screenshot, size, keyframe, path, "
                  "quit; see "
                  "runtime/viewer/script.hpp), then exit");
  cmd->add_option("--size", o->size, "window size WxH; with --script also exactly the size every frame is rendered at");
  cmd->add_option("--camera", o->viewer.camera,
                  "start camera \"position=x,y,z;look_at=x,y,z;up=x,y,z;fov_degrees=DEG\" (aliases pos, at, fov; keys left out keep the scene's camera)");
  cmd->add_option("--path", o->viewer.path,
                  "camera path (.json, as render --path reads) to start with: L plays it, K adds keyframes, "
                  "\"Save path\" writes it back");
  cmd->add_flag("--stay", o->viewer.stay, "after the script, keep the window open for interactive use");
  cmd->add_option("--ao-samples", o->viewer.ao_samples, "ambient-occlusion frames averaged while the camera rests")
      ->check(CLI::Range(1u, 4096u))
      ->capture_default_str();
  add_variant_options(*cmd, o->viewer.variant);
  add_effect_options(*cmd, o->viewer.effects);
  cmd->callback([o] {
    if (!o->size.empty()) o->viewer.size = parse_size(o->size);
    const int status = viewer::run_viewer(o->viewer);
    if (status != 0) throw std::runtime_error("view: stopped before the script's end");
  });
}

}  // namespace nano::cli
