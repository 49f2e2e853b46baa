// `nanoview bench PKG`: what loading and rendering a package cost on this device, and what
// accuracy costs in time.
//   (default)   load time by stage, device memory by category, frame times over a camera path
//               (--path, or an orbit about the scene's camera target) after a warm-up frame
//   --effects   each scene effect off vs on, and all off vs the renderer built without effect code
//   --explicit  explicit instancing (a TLAS of every molecule copy, the conventional design) against
//               virtual instancing: memory and frame time on the same frames, and pixel agreement
//   --counters  the work per pixel at every level of the traversal (queries started, candidates met,
//               tests and rejections; mean and p95), virtual beside explicit instancing on the same
//               view, with what counting costs
//   --matrix    every knob of DESIGN.md's accuracy/time table against the default: time ratio and
//               pixels differing from the CPU oracle (JSON, Markdown table, SVG plot)
//   --medium    the scene's medium (plasma) on and off at the scene camera and a close-up: frame
//               times alternately and the work per pixel of all four (bench_medium.hpp)
//   --compile   every pipeline variant the package's effects and the command-line knobs can select,
//               built cold (no Mesa shader cache, no pipeline cache of ours): SPIR-V size, traversal
//               loops, vkCreateComputePipelines and first-dispatch time
// Variants are always measured alternately in one run, so a noisy shared machine shifts them alike.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "runtime/cli/cli_options.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "runtime/session/accuracy_matrix.hpp"
#include "runtime/bench/frame_stats.hpp"
#include "runtime/bench/on_screen.hpp"
#include "runtime/bench/svg_plot.hpp"
#include "runtime/cli/bench_medium.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/oracle/explicit_scene.hpp"
#include "runtime/oracle/oracle_render.hpp"
#include "runtime/oracle/verify_cameras.hpp"
#include "runtime/explicit_instancing/explicit_vs_virtual.hpp"
#include "runtime/explicit_instancing/work_counters.hpp"
#include "runtime/render/camera_path.hpp"
#include "runtime/render/camera_spec.hpp"
#include "runtime/render/renderer.hpp"
#include "runtime/session/session.hpp"
#include "shared/bindings.h"
#include "runtime/viewer/progressive.hpp"

namespace nano::cli {
namespace {

struct Options {
  std::string package, size, camera, path, json, markdown, plot;
  unsigned frames = 0;
  unsigned matrix_cameras = 4;
  std::vector<std::string> matrix_knobs;  // empty: every knob
  bool effects = false, matrix = false, explicit_instancing = false, counters = false, compile = false, medium = false;
  std::string close_up;  // --medium's close-up camera (empty: chosen on the scene camera's axis)
  bool warm = false;  // with --compile: the caches as they are (the rows checked, not measured cold)
  session::VariantOptions variant;
  session::EffectOptions effect_options;
};

void write_text(const std::string& path, const std::string& text) {
  write_file_atomically(path, std::as_bytes(std::span(text.data(), text.size())));
}

// The cameras of the timed frames: the path's frames, or one turn about the target's up axis.
std::vector<Camera> frame_cameras(const Options& o, const Camera& start, unsigned count) {
  std::vector<Camera> cameras;
  if (!o.path.empty()) {
    const render::CameraPath path = render::read_camera_path(o.path);
    const std::uint64_t n = std::min<std::uint64_t>(path.frame_count(), count);
    for (std::uint64_t k = 0; k < n; ++k) cameras.push_back(render::camera_at(path, path.frame_time(k)));
    return cameras;
  }
  const glm::dvec3 axis = glm::normalize(start.up);
  for (unsigned k = 0; k < count; ++k) {
    const double angle = 2 * M_PI * double(k) / double(count);
    const glm::dvec3 r = start.position - start.look_at;
    // Rodrigues: r turned by `angle` about `axis`.
    const glm::dvec3 turned = r * std::cos(angle) + glm::cross(axis, r) * std::sin(angle) + axis * glm::dot(axis, r) * (1 - std::cos(angle));
    Camera c = start;
    c.position = start.look_at + turned;
    cameras.push_back(c);
  }
  return cameras;
}

nlohmann::ordered_json memory_json(const render::MemoryReport& m) {
  return {{"package_data", m.package_data}, {"derived", m.derived}, {"nlas", m.nlas}, {"mlas", m.mlas},
          {"ulas", m.ulas}, {"flat", m.flat}, {"package_imported_in_place", m.package_imported}, {"build_scratch_peak", m.scratch_peak}};
}

void run_frames(const Options& o, session::RenderSession& session, nlohmann::ordered_json& out) {
  const auto [w, h] = parse_size(o.size.empty() ? "256x256" : o.size);
  const Camera start = session::camera_option(session.package, o.camera);
  render::RenderSettings settings = o.variant.render_settings();
  settings.effects = o.effect_options.settings(session.package);
  settings.focus_distance = render::focus_distance_for(start);
  render::Renderer renderer(session.device, *session.scene, settings);
  const std::vector<Camera> cameras = frame_cameras(o, start, o.frames ? o.frames : 24);
  // Open → first image: what the viewer shows first (a frame at 1/kFirstFrameScale, pipeline
  // compilation included) after the package is mapped, validated and its structures built.
  const render::Frame first = renderer.render(start.to_gpu(viewer::reduced_extent(w, viewer::kFirstFrameScale),
                                                            viewer::reduced_extent(h, viewer::kFirstFrameScale)));
  renderer.render(cameras.front().to_gpu(w, h));  // warm-up: first touch of the full-size buffers
  std::vector<double> seconds;
  std::uint64_t molecules = 0, atoms = 0, hit_pixels = 0;
  for (const Camera& c : cameras) {
    const render::Frame f = renderer.render(c.to_gpu(w, h));
    seconds.push_back(f.seconds);
    const bench::OnScreen seen = bench::on_screen(session.package.records<format::SectionKind::molecules>(), f.hits);
    molecules += seen.copies, atoms += seen.atoms, hit_pixels += seen.hit_pixels;
  }
  const bench::FrameStats stats = bench::frame_stats(seconds);
  const render::LoadReport& load = session.scene->report();
  const session::SessionTimings& t = session.timings;
  const std::uint64_t rays = render::Renderer::rays_per_frame(settings, std::uint64_t(w) * h);
  out["size"] = {w, h};
  out["frames"] = cameras.size();
  out["camera_path"] = o.path.empty() ? "orbit of " + std::to_string(cameras.size()) + " frames about " + start.to_string() : o.path;
  out["load_seconds"] = t.map + t.validate + t.device + t.scene;
  out["first_image_seconds"] = first.seconds;
  // The first image's pipeline: its creation (before the frame, so not in first.seconds) and its
  // first dispatch (in the frame; where a lazily compiling driver generates code). Whether a
  // driver's own shader cache served it decides cold against warm; Mesa says so by one variable,
  // which a cold measurement sets.
  const render::Renderer::PipelineBuild build = renderer.pipeline_build();
  out["open_to_first_image_seconds"] = t.map + t.validate + t.device + t.scene + build.create_seconds + first.seconds;
  const char* mesa_cache_disable = std::getenv("MESA_SHADER_CACHE_DISABLE");
  const bool driver_cache_off = mesa_cache_disable != nullptr && std::string_view(mesa_cache_disable) == "true";
  out["first_image_pipeline_seconds"] = build.create_seconds + std::max(build.first_dispatch_seconds, 0.0);
  out["first_image_shader_cache"] = driver_cache_off ? "off (cold)" : "driver default (warm once this pipeline was built before)";
  out["load_stages_seconds"] = {{"map", t.map},           {"validate", t.validate},      {"device", t.device},
                                {"upload", load.upload_seconds}, {"nlas_builds", load.nlas_seconds},
                                {"mlas_builds", load.mlas_seconds}, {"ulas_builds", load.ulas_seconds},
                                {"scene_total", t.scene}};
  out["frame_seconds"] = bench::to_json(stats);
  out["rays_per_second"] = double(rays) / stats.median;
  out["molecules_on_screen"] = double(molecules) / double(cameras.size());
  out["atoms_of_molecules_on_screen"] = double(atoms) / double(cameras.size());
  out["hit_pixel_fraction"] = double(hit_pixels) / (double(cameras.size()) * w * h);
  out["device_memory_bytes"] = load.memory.total();
  out["device_memory"] = memory_json(load.memory);
  out["flat_level"] = {{"copies", load.flattened_copies}, {"triangles", load.flattened_triangles},
                       {"last_build_seconds", load.flat_seconds}};
  out["acceleration_structures"] = {{"nlas", load.nlas_count}, {"mlas", load.mlas_count}, {"prisms", load.prisms}};
  std::printf("open -> first image %.3f s (a %ux%u frame in %.3f s after the load; pipeline creation and first dispatch %.3f s, "
              "driver shader cache %s)\n",
              double(out["open_to_first_image_seconds"]), first.width, first.height, first.seconds,
              double(out["first_image_pipeline_seconds"]), driver_cache_off ? "off: cold" : "on: warm if built before");
  std::printf("load %.3f s (map %.3f, validate %.3f, device %.3f, upload %.3f, nLAS %.3f, mLAS %.3f, µLAS %.3f)\n",
              double(out["load_seconds"]), t.map, t.validate, t.device, load.upload_seconds, load.nlas_seconds,
              load.mlas_seconds, load.ulas_seconds);
  std::printf("frames %zu at %ux%u: min %.4f s, median %.4f s, p95 %.4f s; %.3g rays/s; %.0f molecules (%.3g atoms) on screen\n",
              cameras.size(), w, h, stats.min, stats.median, stats.p95, double(rays) / stats.median,
              double(molecules) / double(cameras.size()), double(atoms) / double(cameras.size()));
  std::printf("device memory %.2f MB: package %.2f, derived %.2f, nLAS %.2f, mLAS %.2f, µLAS %.2f, flat level %.2f (build "
              "scratch peak %.2f, freed)\n",
              load.memory.total() / 1e6, load.memory.package_data / 1e6, load.memory.derived / 1e6, load.memory.nlas / 1e6,
              load.memory.mlas / 1e6, load.memory.ulas / 1e6, load.memory.flat / 1e6, load.memory.scratch_peak / 1e6);
}

struct EffectVariant {
  std::string name;
  render::RenderSettings settings;
};

// Every effect on its own, with the scene's parameters or the effect table's fallbacks (8 AO rays
// of 40 Å, 5° jitter at 1 Hz), and a cut-away plane through the target when the scene clips nothing.
std::vector<EffectVariant> effect_variants(const render::RenderSettings& base, const render::EffectSettings& scene,
                                           const Camera& camera) {
  render::EffectSettings off;
  off.time = 1.0;
  render::EffectSettings with = scene;
  with.time = 1.0;
  if (!with.clipping.any()) {
    const glm::dvec3 n = glm::normalize(camera.look_at - camera.position);  // keep what lies beyond the target
    with.clipping.planes.push_back(glm::dvec4(n, -glm::dot(n, camera.look_at)));
  }
  std::vector<EffectVariant> v;
  const auto add = [&](std::string name, render::EffectSettings e, bool no_code = false) {
    render::RenderSettings s = base;
    s.effects = e;
    s.without_effect_code = no_code;
    v.push_back({std::move(name), s});
  };
  add("no effect code", off, true);
  add("all off", off);
  for (const EffectDeclaration& effect : effect_table()) {  // every effect of the table alone
    render::EffectSettings e = with;
    e.on = {};
    e.flag(effect.id) = true;
    add(std::string(effect.name), e);
  }
  render::EffectSettings all = with;
  all.on.fill(true);
  add("all on", all);
  return v;
}

struct CompileRow {
  std::string what;                // the effect or knob, as a user selects it
  render::RenderSettings settings;
};

// Every variant a user can select from this package: the scene as `render` draws it, the build
// without effect code, every effect alone, all of them, and every knob flipped from the command's.
std::vector<CompileRow> compile_rows(const render::RenderSettings& command, const render::EffectSettings& scene,
                                     const Camera& camera) {
  std::vector<CompileRow> rows;
  const auto add = [&](std::string what, render::RenderSettings s) { rows.push_back({std::move(what), s}); };
  add("as render draws it", command);
  render::RenderSettings off = command;
  off.effects = render::EffectSettings{};
  off.without_effect_code = true;
  off.lod_pixels = 0;
  add("no effect code", off);
  off.without_effect_code = false;
  add("every effect off", off);
  const std::vector<EffectVariant> effects = effect_variants(off, scene, camera);
  for (const EffectVariant& e : effects)
    if (e.name != "no effect code" && e.name != "all off") add(e.name == "all on" ? "every effect on" : e.name, e.settings);
  const auto knob = [&](std::string what, auto change) {
    render::RenderSettings s = command;
    change(s);
    add(std::move(what), s);
  };
  knob(command.flatten_bytes ? "--flatten off" : "--flatten auto",
       [&](render::RenderSettings& s) { s.flatten_bytes = command.flatten_bytes ? 0 : render::kFlattenAuto; });
  knob("--lod auto", [](render::RenderSettings& s) { s.lod_pixels = 1; });
  knob("--prism aabb", [](render::RenderSettings& s) { s.exact_prism = false; });
  knob("--levels 3", [](render::RenderSettings& s) { s.replication_las = false; });
  knob("--levels 2", [](render::RenderSettings& s) {
    s.two_level = true;
    s.effects.flag(EffectId::clipping) = s.effects.flag(EffectId::jitter) = false;
  });
  knob("--precision camera-relative", [](render::RenderSettings& s) { s.precision = render::Precision::camera_relative; });
  knob("--precision world", [](render::RenderSettings& s) { s.precision = render::Precision::world; });
  knob("bench --counters", [](render::RenderSettings& s) { s.counters = true; });
  return rows;
}

// Each variant built on its own, cold, then dispatched once over one workgroup (8×8 pixels) of the
// scene's view: a driver that compiles at first use (lavapipe: LLVM) does it there.
void run_compile(const Options& o, session::RenderSession& session, nlohmann::ordered_json& out) {
  const Camera camera = session::camera_option(session.package, o.camera);
  render::RenderSettings command = o.variant.render_settings();
  command.effects = o.effect_options.settings(session.package);
  command.focus_distance = render::focus_distance_for(camera);
  const gpu::Camera tile = camera.to_gpu(gpu::NANO_WORKGROUP_SIZE, gpu::NANO_WORKGROUP_SIZE);
  std::map<std::string, std::size_t> built;  // variant name → its row
  std::printf("%-28s %9s %6s %9s %9s %9s  %s\n", "selected by", "SPIR-V kB", "loops", "create s", "dispatch s", "total s",
              "pipeline (specialization constants on)");
  for (const CompileRow& row : compile_rows(command, render::package_effects(session.package), camera)) {
    nlohmann::ordered_json j{{"selected_by", row.what}};
    const std::string name = render::Renderer::variant_name(row.settings);
    j["pipeline"] = name;
    if (const auto same = built.find(name); same != built.end()) {
      j["same_pipeline_as"] = out["variants"][same->second]["selected_by"];
      j["pipeline"] = out["variants"][same->second]["pipeline"];
      std::printf("%-28s %s\n", row.what.c_str(), ("same pipeline as \"" + std::string(j["same_pipeline_as"]) + "\"").c_str());
      out["variants"].push_back(j);
      continue;
    }
    try {
      render::Renderer renderer(session.device, *session.scene, row.settings);
      (void)renderer.render(tile);
      const render::Renderer::PipelineBuild b = renderer.pipeline_build();
      j["pipeline"] = b.variant;  // with the scene's part (small_areas)
      j["spirv_bytes"] = b.spirv_bytes;
      j["ray_query_loops"] = b.ray_query_loops;
      j["create_seconds"] = b.create_seconds;
      j["first_dispatch_seconds"] = b.first_dispatch_seconds;
      j["total_seconds"] = b.create_seconds + b.first_dispatch_seconds;
      std::printf("%-28s %9.1f %6u %9.3f %9.3f %9.3f  %s\n", row.what.c_str(), b.spirv_bytes / 1e3, b.ray_query_loops,
                  b.create_seconds, b.first_dispatch_seconds, b.create_seconds + b.first_dispatch_seconds, b.variant.c_str());
      built.emplace(name, out["variants"].size());
    } catch (const InputError& e) {  // a knob this package cannot take (no beads, no atom squares)
      j["unavailable"] = e.what();
      std::printf("%-28s unavailable: %s\n", row.what.c_str(), e.what());
    }
    out["variants"].push_back(j);
  }
  out["cold"] = o.warm ? "no: --warm, the driver's and our caches as they were" : "MESA_SHADER_CACHE_DISABLE=true, no pipeline cache";
  std::printf("create: vkCreateComputePipelines (SPIR-V to the driver's IR, ray queries lowered); dispatch: the first "
              "dispatch of one workgroup, where a driver that compiles lazily generates code (lavapipe: LLVM)\n");
}

void run_effects(const Options& o, session::RenderSession& session, nlohmann::ordered_json& out) {
  const auto [w, h] = parse_size(o.size.empty() ? "256x256" : o.size);
  const unsigned rounds = o.frames ? o.frames : 5;
  const Camera camera = session::camera_option(session.package, o.camera);
  render::RenderSettings base = o.variant.render_settings();
  base.focus_distance = render::focus_distance_for(camera);
  // Each effect's cost on the virtual traversal: jitter turns the flat level off, which would
  // otherwise be counted against it.
  base.flatten_bytes = 0;
  const std::vector<EffectVariant> variants = effect_variants(base, render::package_effects(session.package), camera);
  render::Renderer renderer(session.device, *session.scene, variants.front().settings);
  const gpu::Camera gpu_camera = camera.to_gpu(w, h);
  std::vector<std::vector<double>> seconds(variants.size());
  // Each round starts one variant later, so no variant always follows the costly "all on" frame.
  for (unsigned round = 0; round <= rounds; ++round)
    for (std::size_t k = 0; k < variants.size(); ++k) {
      const std::size_t v = (k + round) % variants.size();
      renderer.set_settings(variants[v].settings);
      const double s = renderer.render(gpu_camera).seconds;
      if (round > 0) seconds[v].push_back(s);  // round 0 compiles every pipeline
    }
  const double reference = bench::frame_stats(seconds[1]).median;
  out["size"] = {w, h};
  out["rounds"] = rounds;
  out["camera"] = camera.to_string();
  out["reference"] = variants[1].name;
  std::printf("%-16s %12s %12s %14s\n", "variant", "median s", "vs all off", "rays/frame");
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const bench::FrameStats stats = bench::frame_stats(seconds[v]);
    const std::uint64_t rays = render::Renderer::rays_per_frame(variants[v].settings, std::uint64_t(w) * h);
    std::printf("%-16s %12.4f %12.3f %14llu\n", variants[v].name.c_str(), stats.median, stats.median / reference, (unsigned long long)rays);
    out["variants"].push_back({{"name", variants[v].name},
                               {"frame_seconds", bench::to_json(stats)},
                               {"ratio_to_all_off", stats.median / reference},
                               {"rays_per_frame_at_most", rays}});
  }
}

void run_matrix(const Options& o, session::RenderSession& session, nlohmann::ordered_json& out) {
  const auto [w, h] = parse_size(o.size.empty() ? "96x96" : o.size);
  const unsigned rounds = o.frames ? o.frames : 3;
  if (o.variant.shell != "adaptive-overlap" || o.variant.levels != "3+rep" || o.variant.prism != "exact")
    throw InputError("--matrix", "", "measures every knob against the defaults; leave --shell, --levels and --prism out");
  std::vector<session::MatrixVariant> variants = session::matrix_variants(o.variant.render_settings(), session.package);
  if (!o.matrix_knobs.empty()) variants = session::select_matrix_knobs(std::move(variants), o.matrix_knobs, "--matrix-knobs");
  const oracle::ExplicitScene scene(session.package);
  // The verify views (near: the hard cases first) and the package's own camera (far: the overview,
  // where the level of detail acts) when the CPU oracle can resolve it (a whole cell cannot).
  std::vector<gpu::Camera> cameras;
  for (const oracle::VerifyCamera& vc : oracle::verify_cameras(session.package, scene, o.matrix_cameras))
    cameras.push_back(vc.view.to_gpu(w, h));
  const gpu::Camera far = session::camera_option(session.package, o.camera).to_gpu(w, h);
  std::vector<session::KnownOracleImage> effect_free;  // the far view's, made by the probe
  try {
    oracle::OracleRenderOptions probe;
    probe.camera_name = "the matrix's far view";
    probe.ray_tubes = false;  // a view the rounds cannot hold is left out, not traced ray by ray
    effect_free.push_back({cameras.size(), oracle::oracle_render(scene, session.package, far, probe)});
    cameras.push_back(far);
  } catch (const InputError& e) {
    std::fprintf(stderr, "matrix: far view left out: %s\n", e.what());
  }
  const std::vector<session::MatrixRow> rows = session::run_accuracy_matrix(
      session.device, session.package, *session.scene, cameras, variants, rounds, effect_free,
      [](const std::string& what) { std::fprintf(stderr, "matrix: %s\n", what.c_str()); });
  out["size"] = {w, h};
  out["cameras"] = cameras.size();
  out["rounds"] = rounds;
  out["matrix"] = session::to_json(rows);
  const std::string heading = "Accuracy/time matrix of " + session.package.name() + " on " + session.device.description() + ", " +
                              std::to_string(cameras.size()) + " verify views at " + std::to_string(w) + "×" + std::to_string(h) +
                              ", " + std::to_string(rounds) + " rounds";
  // The level of detail's own views: the scene camera and the same view from four times as far,
  // against full detail (no oracle reaches a whole cell).
  const Camera scene_camera = session::camera_option(session.package, o.camera);
  Camera farther = scene_camera;
  farther.position = scene_camera.look_at + 4.0 * (scene_camera.position - scene_camera.look_at);
  const std::vector<session::LodFarRow> far_rows = session::run_lod_far_views(
      session.device, *session.scene, {{"scene camera", far}, {"4× as far", farther.to_gpu(w, h)}}, variants, rounds,
      [](const std::string& what) { std::fprintf(stderr, "matrix: %s\n", what.c_str()); });
  out["lod_far_views"] = session::to_json(far_rows);
  const std::string md = session::matrix_markdown(rows, heading) + session::lod_far_markdown(far_rows);
  std::printf("%s", md.c_str());
  if (!o.markdown.empty()) write_text(o.markdown, md);
  if (!o.plot.empty())
    write_text(o.plot, bench::svg_plot(session::matrix_plot(rows, "Error against time: " + std::filesystem::path(session.package.name()).filename().string()),
                                       "--plot"));
}

void run_explicit(const Options& o, session::RenderSession& session, nlohmann::ordered_json& out) {
  const auto [w, h] = parse_size(o.size.empty() ? "128x128" : o.size);
  const unsigned rounds = o.frames ? o.frames : 3;
  std::vector<gpu::Camera> cameras;
  for (const Camera& c : frame_cameras(o, session::camera_option(session.package, o.camera), 4)) cameras.push_back(c.to_gpu(w, h));
  const explicit_instancing::ExplicitVsVirtual r =
      explicit_instancing::compare_explicit_and_virtual(session.device, session.package, *session.scene, cameras, rounds,
                                              o.variant.render_settings());
  out["size"] = {w, h};
  out["explicit_vs_virtual"] = r.to_json();
  std::printf("%llu copies; frame median: explicit %.4f s, virtual %.4f s (virtual / explicit %.2f); device memory: explicit "
              "%.2f MB, virtual %.2f MB; pixel agreement %.5f over %llu frames each\n",
              (unsigned long long)r.copies, r.explicit_seconds_median, r.virtual_seconds_median,
              r.virtual_seconds_median / r.explicit_seconds_median, r.explicit_device_bytes / 1e6, r.virtual_device_bytes / 1e6,
              r.agreement, (unsigned long long)r.frames);
}

void run_counters(const Options& o, session::RenderSession& session, nlohmann::ordered_json& out) {
  const auto [w, h] = parse_size(o.size.empty() ? "128x128" : o.size);
  const unsigned rounds = o.frames ? o.frames : 3;
  const Camera camera = session::camera_option(session.package, o.camera);
  const explicit_instancing::WorkCounters r = explicit_instancing::count_work(session.device, session.package, *session.scene,
                                                          {camera.to_gpu(w, h)}, rounds, o.variant.render_settings());
  out["size"] = {w, h};
  out["camera"] = camera.to_string();
  out["work"] = r.to_json();
  std::vector<std::pair<std::string, bench::CounterSummary>> columns{{"virtual", r.virtual_work}};
  if (r.explicit_work) columns.emplace_back("explicit", *r.explicit_work);
  std::printf("%s", bench::counters_markdown(columns).c_str());
  std::printf("frame median: virtual %.4f s; counting costs %.2f×; the counters constant off against no counter code %.3f×; "
              "counting changes %s\n",
              r.virtual_seconds, r.virtual_counting_seconds / r.virtual_seconds,
              r.virtual_seconds / r.virtual_no_counter_code_seconds, r.counting_changes_no_pixel ? "no pixel" : "PIXELS");
  if (r.explicit_work)
    std::printf("explicit %.4f s (virtual / explicit %.2f); agreement %.5f\n", r.explicit_seconds,
                r.virtual_seconds / r.explicit_seconds, r.agreement);
  else
    std::printf("explicit instancing left out: %s\n", r.explicit_skipped.c_str());
}

void run_medium(const Options& o, session::RenderSession& session, nlohmann::ordered_json& out) {
  MediumBenchOptions m;
  if (!o.size.empty()) m.size = o.size;
  if (o.frames) m.rounds = o.frames;
  m.scene_camera = o.camera;
  m.close_up = o.close_up;
  m.settings = o.variant.render_settings();
  m.settings.effects = o.effect_options.settings(session.package);
  run_medium_bench(m, session, out);
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("bench", "Measure load and frame times, memory, effect costs and the accuracy/time matrix on this device");
  cmd->add_option("PKG", o->package, "package (.nup)")->required();
  cmd->add_option("--size", o->size, "image size WxH (default 256x256; --matrix 96x96)");
  cmd->add_option("--frames", o->frames, "timed frames (default 24), or rounds with --effects (5) and --matrix (3)")
      ->check(CLI::Range(1u, 10000u));
  cmd->add_option("--path", o->path, "camera path (.json) of the timed frames (default: an orbit about the scene's target)");
  cmd->add_option("--camera", o->camera, "\"position=..;look_at=..;up=..;fov_degrees=..\" (aliases pos, at, fov) start of the orbit / the --effects and --explicit view");
  cmd->add_option("--json", o->json, "write the results as JSON");
  cmd->add_flag("--effects", o->effects, "each effect off vs on, and all off vs the renderer without effect code");
  cmd->add_flag("--explicit", o->explicit_instancing,
                "explicit instancing (one TLAS instance per molecule copy) against virtual instancing on the same frames");
  cmd->add_flag("--counters", o->counters,
                "work per pixel at every traversal level, virtual beside explicit instancing (default 128x128, 3 timed rounds)");
  cmd->add_flag("--compile", o->compile,
                "every pipeline variant the package's effects and the knobs select, built cold: SPIR-V size, "
                "traversal loops, create and first-dispatch time");
  cmd->add_flag("--warm", o->warm,
                "with --compile: leave the driver's shader cache and ours as they are (lists and builds the rows; "
                "the times are then not cold)");
  cmd->add_flag("--medium", o->medium,
                "the scene's medium on and off at the scene camera (--camera) and a close-up in it: frame times and the "
                "work per pixel at every level (default 128x128, 5 rounds)");
  cmd->add_option("--close-up", o->close_up,
                  "with --medium: the close-up's camera (default: 600 Å before the first atom on the scene camera's axis)");
  cmd->add_flag("--matrix", o->matrix, "every accuracy knob against the default: time ratio and pixels differing from the oracle");
  cmd->add_option("--matrix-cameras", o->matrix_cameras, "verify views of the matrix")->capture_default_str()->check(CLI::Range(1u, 16u));
  cmd->add_option("--matrix-knobs", o->matrix_knobs,
                  "with --matrix: only these knobs' rows beside the default (comma-separated, as the table names them, "
                  "'-' for a space: flat-level; a name it lacks lists them)")
      ->delimiter(',');
  cmd->add_option("--markdown", o->markdown, "with --matrix: write the table as Markdown");
  cmd->add_option("--plot", o->plot, "with --matrix: write error against time as SVG");
  add_variant_options(*cmd, o->variant);
  add_effect_options(*cmd, o->effect_options);
  cmd->callback([o] {
    if (int(o->effects) + int(o->matrix) + int(o->explicit_instancing) + int(o->counters) + int(o->compile) + int(o->medium) > 1)
      throw InputError("--effects/--matrix/--explicit/--counters/--compile/--medium", "", "choose one mode");
    if (!o->close_up.empty() && !o->medium) throw InputError("--close-up", "", "needs --medium");
    if ((!o->markdown.empty() || !o->plot.empty()) && !o->matrix) throw InputError("--markdown/--plot", "", "need --matrix");
    if (!o->matrix_knobs.empty() && !o->matrix) throw InputError("--matrix-knobs", "", "needs --matrix");
    session::SessionOptions session_options = o->variant.scene_options();
    if (o->warm && !o->compile) throw InputError("--warm", "", "needs --compile");
    if (o->compile && !o->warm) {
      // Cold: Mesa's disk cache off (read when the device opens) and no pipeline cache of ours.
      setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
      session_options.persistent_pipeline_cache = false;
    }
    session::RenderSession session(o->package, session_options);
    nlohmann::ordered_json out;
    out["package"] = o->package;
    out["package_bytes"] = session.package.file_size();
    out["device"] = session.device.description();
    out["mode"] = o->effects ? "effects" : o->matrix ? "matrix" : o->explicit_instancing ? "explicit" : o->counters ? "counters"
                  : o->compile ? "compile" : o->medium ? "medium" : "frames";
    std::printf("%s on %s\n", o->package.c_str(), session.device.description().c_str());
    if (o->effects) run_effects(*o, session, out);
    else if (o->matrix) run_matrix(*o, session, out);
    else if (o->explicit_instancing) run_explicit(*o, session, out);
    else if (o->counters) run_counters(*o, session, out);
    else if (o->compile) run_compile(*o, session, out);
    else if (o->medium) run_medium(*o, session, out);
    else run_frames(*o, session, out);
    out["validation_errors"] = session.validation_errors();
    if (!o->json.empty()) write_text(o->json, out.dump(2) + "\n");
    if (session.validation_errors() != 0)
      throw std::runtime_error("the Vulkan validation layer reported " + std::to_string(session.validation_errors()) + " error(s)");
  });
}

}  // namespace nano::cli
