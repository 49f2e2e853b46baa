#include "runtime/cli/bench_medium.hpp"

#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "common/error.hpp"
#include "format/package_view.hpp"
#include "runtime/bench/frame_stats.hpp"
#include "runtime/bench/on_screen.hpp"
#include "runtime/bench/ray_counters.hpp"
#include "runtime/cli/commands.hpp"

namespace nano::cli {
namespace {

struct View {
  std::string name;
  Camera camera;
};

// The compartment instance nearest the scene camera's target, seen from the scene camera: the first
// atom on that line with the medium hidden, and a camera `gap` Å before it looking on.
Camera close_up_of(const MediumBenchOptions& o, session::RenderSession& session, const Camera& scene_camera) {
  Camera scene = scene_camera;
  double nearest = INFINITY;
  for (const gpu::CompartmentInstance& ci : session.package.records<format::SectionKind::compartment_instances>()) {
    const glm::dvec3 centre = format::instance_transform(ci).translation;
    if (glm::length(centre - scene_camera.look_at) < nearest) nearest = glm::length(centre - scene_camera.look_at), scene.look_at = centre;
  }
  render::RenderSettings probe = o.settings;
  probe.show_medium = false;
  probe.counters = false;
  render::Renderer renderer(session.device, *session.scene, probe);
  const render::Frame frame = renderer.render(scene.to_gpu(1, 1));
  const float depth = frame.hits.front().depth;
  if (frame.hits.front().atom == gpu::kNoHit || !std::isfinite(depth))
    throw InputError("--close-up", "", "the line from the scene camera to the nearest cell meets no atom: give the close-up's camera");
  const glm::dvec3 axis = glm::normalize(scene.look_at - scene.position);
  Camera c = scene;
  c.position = scene.position + axis * std::max(0.0, double(depth) - o.close_up_gap);
  c.look_at = c.position + axis * o.close_up_gap;
  c.fov_degrees = 30;
  return c;
}

struct Column {
  std::string name;
  gpu::Camera camera;
  render::RenderSettings settings;
  std::vector<double> seconds;
  double hit_fraction = 0;
};

}  // namespace

void run_medium_bench(const MediumBenchOptions& o, session::RenderSession& session, nlohmann::ordered_json& out) {
  if (!session.scene->has_medium()) throw InputError(session.package.name(), "", "--medium: the package has no medium");
  const auto [w, h] = parse_size(o.size);
  const Camera scene = session::camera_option(session.package, o.scene_camera);
  const Camera close = o.close_up.empty() ? close_up_of(o, session, scene) : session::camera_option(session.package, o.close_up);
  std::vector<Column> columns;
  for (const View& v : {View{"scene camera", scene}, View{"close-up", close}})
    for (const bool medium : {true, false}) {
      Column c{v.name + (medium ? ", plasma" : ", no plasma"), v.camera.to_gpu(w, h), o.settings, {}, 0};
      c.settings.show_medium = medium;
      c.settings.counters = false;
      columns.push_back(std::move(c));
    }
  render::Renderer renderer(session.device, *session.scene, columns.front().settings);
  for (unsigned round = 0; round <= o.rounds; ++round)  // round 0 builds the pipelines
    for (Column& c : columns) {
      renderer.set_settings(c.settings);
      const render::Frame f = renderer.render(c.camera);
      if (round == 0) continue;
      c.seconds.push_back(f.seconds);
      const bench::OnScreen seen = bench::on_screen(session.package.records<format::SectionKind::molecules>(), f.hits);
      c.hit_fraction = double(seen.hit_pixels) / double(f.hits.size());
    }
  std::vector<std::pair<std::string, bench::CounterSummary>> work;
  for (const Column& c : columns) {
    render::RenderSettings counting = c.settings;
    counting.counters = true;
    renderer.set_settings(counting);
    work.emplace_back(c.name, bench::summarize_counters(renderer.render(c.camera).counters));
  }
  out["size"] = {w, h};
  out["rounds"] = o.rounds;
  out["scene_camera"] = scene.to_string();
  out["close_up"] = close.to_string();
  std::printf("scene camera: %s\nclose-up: %s\n\n| view | frame median | with / without plasma | pixels hit |\n|---|---|---|---|\n",
              scene.to_string().c_str(), close.to_string().c_str());
  for (std::size_t k = 0; k < columns.size(); ++k) {
    const bench::FrameStats stats = bench::frame_stats(columns[k].seconds);
    const double without = bench::frame_stats(columns[k | 1].seconds).median;
    std::printf("| %s | %.4f s | %.2f× | %.1f %% |\n", columns[k].name.c_str(), stats.median, stats.median / without,
                100 * columns[k].hit_fraction);
    out["views"].push_back({{"name", columns[k].name}, {"frame_seconds", bench::to_json(stats)},
                            {"ratio_to_without_plasma", stats.median / without}, {"hit_pixel_fraction", columns[k].hit_fraction},
                            {"work", bench::to_json(work[k].second)}});
  }
  std::printf("\nWork per pixel (mean, p95):\n%s", bench::counters_markdown(work).c_str());
}

}  // namespace nano::cli
