// `nanoview render PKG -o out.png [--size WxH] [--camera SPEC] [--depth out.pfm] [--ids out.bin]
//  [--shell MODE] [--prism exact|aabb] [--levels 3+rep|3] [--frames N]`: one frame of the ray-query renderer, written atomically.
#include <algorithm>
#include <cstdio>
#include <vector>
#include <memory>
#include <string>

#include "common/error.hpp"
#include "runtime/commands.hpp"
#include "runtime/render/camera_spec.hpp"
#include "runtime/render/image_io.hpp"
#include "runtime/render/renderer.hpp"
#include "runtime/render_session.hpp"

namespace nano::view {

std::pair<std::uint32_t, std::uint32_t> parse_size(const std::string& text) {
  unsigned w = 0, h = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%ux%u%c", &w, &h, &tail) != 2 || w == 0 || h == 0 || w > 16384 || h > 16384)
    throw InputError("--size", "", "expected WxH with 1 ≤ W, H ≤ 16384, got '" + text + "'");
  return {w, h};
}

void add_render_command(CLI::App& app) {
  struct Options {
    std::string package, output, size = "384x384", camera, depth, ids;
    unsigned frames = 1;
    VariantOptions variant;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("render", "Render one frame of a package with nested ray queries (PNG, depth PFM, hit ids)");
  cmd->add_option("PKG", o->package, "package (.nup)")->required();
  cmd->add_option("-o,--output", o->output, "colour image (.png)")->required();
  cmd->add_option("--size", o->size, "image size WxH")->capture_default_str();
  cmd->add_option("--camera", o->camera,
                  "\"pos=x,y,z;at=x,y,z;up=x,y,z;fov=DEG\" (world Å, vertical fov); keys left out keep the scene's camera");
  cmd->add_option("--depth", o->depth, "depth along the unit ray in Å as PFM (+inf: background)");
  cmd->add_option("--ids", o->ids, "per-pixel hit ids (see README)");
  o->variant.add_to(*cmd);
  cmd->add_option("--frames", o->frames,
                  "render the frame this many times and report the min and median time of all but the first "
                  "(the first dispatch compiles the shader)")
      ->check(CLI::Range(1u, 1000u));
  cmd->callback([o] {
    const auto [w, h] = parse_size(o->size);
    render::RenderSettings settings = o->variant.render_settings();
    RenderSession session(o->package, o->variant.scene_options());
    render::CameraSpec camera = render::package_camera(session.package);
    try {
      if (!o->camera.empty()) camera = render::parse_camera(o->camera, camera);
    } catch (const std::invalid_argument& e) {
      throw InputError("--camera", "", e.what());
    }
    settings.depth_cue = float(4 * glm::length(camera.at - camera.eye));
    render::Renderer renderer(session.device, *session.scene, settings);
    const gpu::Camera gpu_camera = camera.to_gpu(w, h);
    const render::Frame frame = renderer.render(gpu_camera);
    std::vector<double> times;
    for (unsigned k = 1; k < o->frames; ++k) times.push_back(renderer.render(gpu_camera).seconds);
    std::size_t hit = 0;
    for (const auto& p : frame.hits) hit += p.atom != gpu::kNoHit;
    render::write_png(o->output, w, h, frame.rgba);
    if (!o->depth.empty()) render::write_depth_pfm(o->depth, w, h, frame.hits);
    if (!o->ids.empty()) render::write_ids(o->ids, w, h, frame.hits);
    if (!times.empty()) {
      std::sort(times.begin(), times.end());
      std::printf("frames after the first: %zu, min %.4f s, median %.4f s\n", times.size(), times.front(),
                  times[times.size() / 2]);
    }
    const render::LoadReport& load = session.scene->report();
    std::printf("%s: %ux%u, %zu of %zu pixels hit an atom, frame %.3f s; camera %s\n", o->output.c_str(), w, h, hit,
                frame.hits.size(), frame.seconds, camera.to_string().c_str());
    std::printf("load: upload %.3f s, nLAS %.3f s, mLAS %.3f s, µLAS %.3f s; device memory %.2f MB "
                "(package %.2f, derived %.2f, nLAS %.2f, mLAS %.2f, µLAS %.2f; build scratch peak %.2f, freed); "
                "%.2f MB of %llu sections read in place from the mapped package\n",
                load.upload_seconds, load.nlas_seconds, load.mlas_seconds, load.ulas_seconds, load.memory.total() / 1e6,
                load.memory.package_data / 1e6, load.memory.derived / 1e6, load.memory.nlas / 1e6, load.memory.mlas / 1e6,
                load.memory.ulas / 1e6, load.memory.scratch_peak / 1e6, load.memory.package_imported / 1e6, (unsigned long long)load.sections_imported);
    if (session.validation_errors() != 0)
      throw std::runtime_error("the Vulkan validation layer reported " + std::to_string(session.validation_errors()) + " error(s)");
  });
}

}  // namespace nano::view
