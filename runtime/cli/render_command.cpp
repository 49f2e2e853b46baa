// `nanoview render PKG -o out.png [--size WxH] [--camera SPEC] [--depth out.pfm] [--ids out.bin]
//  [--shell MODE] [--prism exact|aabb] [--levels 3+rep|3|2] [--repeat N] [effect options, --time S]`:
//  one frame of the ray-query renderer; `--path cam.json [--frames A:B] -o frames/%05d.png`: frames
//  of a camera path (docs/rendering.md, "Movies"). Every file is written atomically.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>

#include "runtime/cli/cli_options.hpp"
#include "common/error.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/render/camera_path.hpp"
#include "runtime/render/camera_spec.hpp"
#include "runtime/render/image_io.hpp"
#include "runtime/render/renderer.hpp"
#include "runtime/bench/frame_stats.hpp"
#include "runtime/session/session.hpp"

namespace nano::cli {

std::pair<std::uint32_t, std::uint32_t> parse_size(const std::string& text) {
  return render::parse_image_size(text, "--size");
}

namespace {

// "A:B" → frames A … B of the path, inclusive.
std::pair<std::uint64_t, std::uint64_t> parse_frame_range(const std::string& text, std::uint64_t frame_count) {
  unsigned long long a = 0, b = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%llu:%llu%c", &a, &b, &tail) != 2 || text.find('-') != std::string::npos || a > b)
    throw InputError("--frames", "", "expected A:B with frame numbers 0 ≤ A ≤ B, got '" + text + "'");
  if (b >= frame_count)
    throw InputError("--frames", "", "frame " + std::to_string(b) + " is past the path's last frame " +
                                         std::to_string(frame_count - 1));
  return {a, b};
}

std::string frame_output(const std::string& pattern, std::uint64_t frame) {
  const std::filesystem::path path = render::frame_file_name(pattern, frame);
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  return path.string();
}

struct RenderOptions {
  std::string package, output, size = "384x384", camera, depth, ids, path, frames;
  unsigned repeat = 1;
  session::VariantOptions variant;
  session::EffectOptions effects;
};

std::size_t count_hits(const render::Frame& frame) {
  std::size_t hit = 0;
  for (const auto& p : frame.hits) hit += p.atom != gpu::kNoHit;
  return hit;
}

// The frames of a movie, checked before the package reaches the device: the range, and that every
// output is a frame pattern.
std::pair<std::uint64_t, std::uint64_t> movie_frames(const RenderOptions& o, const render::CameraPath& path) {
  const auto range = o.frames.empty() ? std::pair<std::uint64_t, std::uint64_t>{0, path.frame_count() - 1}
                                      : parse_frame_range(o.frames, path.frame_count());
  if (o.repeat > 1) throw InputError("--repeat", "", "times one frame; it cannot be combined with a path's frames");
  const std::pair<const char*, const std::string*> patterns[] = {{"-o", &o.output}, {"--depth", &o.depth}, {"--ids", &o.ids}};
  for (const auto& [option, pattern] : patterns)
    if (!pattern->empty()) render::check_frame_pattern(*pattern, option);
  return range;
}

void render_movie(const RenderOptions& o, const render::CameraPath& path, std::pair<std::uint64_t, std::uint64_t> frames,
                  render::Renderer& renderer, render::RenderSettings settings, std::uint32_t w, std::uint32_t h) {
  for (std::uint64_t k = frames.first; k <= frames.second; ++k) {
    const double time = path.frame_time(k);
    const Camera frame_camera = render::camera_at(path, time);
    // Exactly what `render --camera <frame_camera> --time <time>` would use, so a movie frame can be
    // re-rendered alone; neither changes the compiled pipeline.
    settings.focus_distance = render::focus_distance_for(frame_camera);
    settings.effects.time = time;
    renderer.set_settings(settings);
    const render::Frame frame = renderer.render(frame_camera.to_gpu(w, h));
    const std::string output = frame_output(o.output, k);
    render::write_png(output, w, h, frame.rgba);
    if (!o.depth.empty()) render::write_depth_pfm(frame_output(o.depth, k), w, h, frame.hits);
    if (!o.ids.empty()) render::write_ids(frame_output(o.ids, k), w, h, frame.hits);
    std::printf("%s: frame %llu, time %.4f s, %zu of %zu pixels hit an atom, %.3f s; camera %s\n", output.c_str(),
                (unsigned long long)k, time, count_hits(frame), frame.hits.size(), frame.seconds,
                frame_camera.to_string().c_str());
    std::fflush(stdout);  // progress of a long movie job shows in its log as it goes
  }
}

void render_still(const RenderOptions& o, const Camera& camera, render::Renderer& renderer, std::uint32_t w, std::uint32_t h) {
  const gpu::Camera gpu_camera = camera.to_gpu(w, h);
  const render::Frame frame = renderer.render(gpu_camera);
  std::vector<double> times;
  for (unsigned k = 1; k < o.repeat; ++k) times.push_back(renderer.render(gpu_camera).seconds);
  render::write_png(o.output, w, h, frame.rgba);
  if (!o.depth.empty()) render::write_depth_pfm(o.depth, w, h, frame.hits);
  if (!o.ids.empty()) render::write_ids(o.ids, w, h, frame.hits);
  if (!times.empty()) {
    const bench::FrameStats stats = bench::frame_stats(times);
    std::printf("frames after the first: %zu, min %.4f s, median %.4f s\n", stats.frames, stats.min, stats.median);
  }
  std::printf("%s: %ux%u, %zu of %zu pixels hit an atom, frame %.3f s; camera %s\n", o.output.c_str(), w, h,
              count_hits(frame), frame.hits.size(), frame.seconds, camera.to_string().c_str());
}

void print_load(const render::LoadReport& load) {
  std::printf("load: upload %.3f s, nLAS %.3f s, mLAS %.3f s, µLAS %.3f s; device memory %.2f MB "
              "(package %.2f, derived %.2f, nLAS %.2f, mLAS %.2f, µLAS %.2f, flat level %.2f for %llu copies; build "
              "scratch peak %.2f, freed); %.2f MB of %llu sections read in place from the mapped package\n",
              load.upload_seconds, load.nlas_seconds, load.mlas_seconds, load.ulas_seconds, load.memory.total() / 1e6,
              load.memory.package_data / 1e6, load.memory.derived / 1e6, load.memory.nlas / 1e6, load.memory.mlas / 1e6,
              load.memory.ulas / 1e6, load.memory.flat / 1e6, (unsigned long long)load.flattened_copies,
              load.memory.scratch_peak / 1e6, load.memory.package_imported / 1e6, (unsigned long long)load.sections_imported);
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  auto* cmd = app.add_subcommand("render", "Render one frame of a package, or frames of a camera path, with nested ray queries "
                                           "(PNG, depth PFM, hit ids)");
  cmd->add_option("PKG", o->package, "package (.nup)")->required();
  cmd->add_option("-o,--output", o->output, "colour image (.png); with --path a pattern such as frames/%05d.png")->required();
  cmd->add_option("--size", o->size, "image size WxH")->capture_default_str();
  auto* camera_flag = cmd->add_option(
      "--camera", o->camera, "\"position=x,y,z;look_at=x,y,z;up=x,y,z;fov_degrees=DEG\" (world Å, vertical; aliases pos, at, fov); keys left out keep the scene's camera");
  cmd->add_option("--depth", o->depth, "depth along the unit ray in Å as PFM (+inf: background); a pattern with --path");
  cmd->add_option("--ids", o->ids, "per-pixel hit ids (docs/rendering.md, \"Ids\"); a pattern with --path");
  add_variant_options(*cmd, o->variant);
  add_effect_options(*cmd, o->effects);  // --time among them: with --path also the camera's time (-o is then one file)
  auto* path_option = cmd->add_option("--path", o->path, "camera path (.json, docs/rendering.md \"Movies\"): render its frames")
                          ->excludes(camera_flag);
  auto* frames_option =
      cmd->add_option("--frames", o->frames, "A:B: frames A to B inclusive of --path, frame k at time k / fps (default: all)")
          ->needs(path_option);
  frames_option->excludes(cmd->get_option("--time"));
  cmd->add_option("--repeat", o->repeat,
                  "render one frame this many times and report the min and median time of all but the first "
                  "(the first dispatch compiles the shader)")
      ->check(CLI::Range(1u, 1000u));
  cmd->callback([o, cmd] {
    const auto [w, h] = parse_size(o->size);
    // Everything the user typed is checked before the package reaches the device.
    std::optional<render::CameraPath> path;
    if (!o->path.empty()) path = render::read_camera_path(o->path);
    const bool movie = path && cmd->count("--time") == 0;
    std::pair<std::uint64_t, std::uint64_t> frames{0, 0};
    if (movie) frames = movie_frames(*o, *path);
    render::RenderSettings settings = o->variant.render_settings();
    session::RenderSession session(o->package, o->variant.scene_options());
    settings.effects = o->effects.settings(session.package);
    Camera camera = session::camera_option(session.package, o->camera);
    if (path) camera = render::camera_at(*path, settings.effects.time);
    settings.focus_distance = render::focus_distance_for(camera);
    render::Renderer renderer(session.device, *session.scene, settings);
    if (movie) render_movie(*o, *path, frames, renderer, settings, w, h);
    else render_still(*o, camera, renderer, w, h);
    print_load(session.scene->report());
    if (session.validation_errors() != 0)
      throw std::runtime_error("the Vulkan validation layer reported " + std::to_string(session.validation_errors()) + " error(s)");
  });
}

}  // namespace nano::cli
