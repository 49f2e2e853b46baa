#include "common/effect_table.hpp"
#include "common/error.hpp"
#include "runtime/session/accuracy_matrix.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>

#include "runtime/bench/frame_stats.hpp"
#include "runtime/bench/ray_counters.hpp"
#include "runtime/oracle/oracle_render.hpp"
#include "runtime/oracle/render_compare.hpp"
#include "runtime/session/oracle_view.hpp"
#include "runtime/session/session.hpp"

namespace nano::session {
namespace {

constexpr double kClipViewDepth = 400;  // Å from the eye: views' targets lie ~100–300 Å away

// What the oracle must know of a variant's effects: only clipping, jitter and animation change
// which atom a pixel shows.
// The matrix's clipping: per view, a plane 400 Å ahead of the eye, facing it, keeps the near
// side, so every view keeps what it looks at and the oracle resolves it without walking the far,
// removed side (the package's own planes would leave some verify views looking into nothing).
render::EffectSettings effects_for_view(render::EffectSettings e, const gpu::Camera& camera) {
  if (!e.flag(EffectId::clipping)) return e;
  const glm::dvec3 forward(glm::vec3(camera.forward));
  const glm::dvec3 beyond = glm::dvec3(glm::vec3(camera.position)) + forward * kClipViewDepth;
  e.clipping.planes = {glm::dvec4(-forward, glm::dot(forward, beyond))};
  e.clipping.box.reset();
  return e;
}

// What the oracle's picture depends on (oracle_effects): clipping, jitter, animation, and the time
// only when something moves, so the colour-only effects share the default's images.
std::string oracle_key(const render::EffectSettings& e) {
  const bool jitter = e.flag(EffectId::jitter), animation = e.flag(EffectId::animation);
  char key[160];
  std::snprintf(key, sizeof key, "c%d j%d a%d t%.9g", int(e.flag(EffectId::clipping) && e.clipping.any()), int(jitter), int(animation),
                jitter || animation ? e.time : 0.0);
  return key;
}

// One frame of a variant and one of its reference, the order flipping per round, so both see the
// same machine.
void time_alternately(unsigned round, render::Renderer& variant, render::Renderer& reference, const gpu::Camera& camera,
                      std::vector<double>& variant_seconds, std::vector<double>& reference_seconds) {
  if (round % 2 == 0) {
    variant_seconds.push_back(variant.render(camera).seconds);
    reference_seconds.push_back(reference.render(camera).seconds);
  } else {
    reference_seconds.push_back(reference.render(camera).seconds);
    variant_seconds.push_back(variant.render(camera).seconds);
  }
}

// The variant the others are measured against (the last marked default); `who` names the caller in
// the error when there is none.
const MatrixVariant& default_variant(const std::vector<MatrixVariant>& variants, const char* who) {
  const MatrixVariant* found = nullptr;
  for (const MatrixVariant& v : variants)
    if (v.is_default) found = &v;
  if (!found) throw std::invalid_argument(std::string(who) + ": no default variant");
  return *found;
}

// Oracle images per effect signature and camera, made once.
class OracleImages {
 public:
  OracleImages(const format::Package& package, const std::vector<gpu::Camera>& cameras, const Progress& progress)
      : package_(package), cameras_(cameras), progress_(progress) {}

  // An image made elsewhere, of view k with effects e, is not made again.
  void add(const render::EffectSettings& e, std::size_t k, std::vector<gpu::PixelHit> image) {
    images_.emplace(std::pair{oracle_key(e), k}, std::move(image));
  }

  const std::vector<gpu::PixelHit>& of(const render::EffectSettings& e, std::size_t k) {
    const std::string key = oracle_key(e);
    auto it = images_.find({key, k});
    if (it != images_.end()) return it->second;
    if (progress_) progress_("oracle for " + key + ", view " + std::to_string(k));
    const OracleEffects o = oracle_effects(package_, e);
    const oracle::ExplicitScene scene(package_, o.scene);
    oracle::OracleRenderOptions options;
    options.camera_name = "matrix view " + std::to_string(k);
    options.clip = o.clip;
    return images_.emplace(std::pair{key, k}, oracle::oracle_render(scene, package_, cameras_[k], options)).first->second;
  }

 private:
  const format::Package& package_;
  const std::vector<gpu::Camera>& cameras_;
  const Progress& progress_;
  std::map<std::pair<std::string, std::size_t>, std::vector<gpu::PixelHit>> images_;
};

// Every view with its own settings (the clipping plane follows the view).
std::vector<render::RenderSettings> per_view_settings(const render::RenderSettings& settings,
                                                      const std::vector<gpu::Camera>& cameras) {
  std::vector<render::RenderSettings> per_view;
  for (const gpu::Camera& c : cameras) {
    per_view.push_back(settings);
    per_view.back().effects = effects_for_view(settings.effects, c);
  }
  return per_view;
}

// Warm-up and accuracy: one frame per camera against the oracle.
void measure_accuracy(render::Renderer& renderer, const render::GpuScene& target, const std::vector<gpu::Camera>& cameras,
                      const std::vector<render::RenderSettings>& per_view, OracleImages& oracle_images, MatrixRow& row) {
  std::uint64_t agree = 0;
  for (std::size_t k = 0; k < cameras.size(); ++k) {
    renderer.set_settings(per_view[k]);
    const render::Frame f = renderer.render(cameras[k]);
    // The flat level's share follows the view: the most any view took.
    row.device_bytes = std::max<std::uint64_t>(row.device_bytes, target.report().memory.total());
    const oracle::CompareResult r =
        oracle::compare_images(oracle_images.of(per_view[k].effects, k), f.hits, cameras[k].size.x, cameras[k].size.y, 0);
    agree += r.agree, row.pixels += r.pixels;
  }
  row.wrong_percent = row.pixels ? 100.0 * double(row.pixels - agree) / double(row.pixels) : 0.0;
}

// Work: every view once more with the counters on (their own pipeline, outside the timing).
void measure_work(render::Renderer& renderer, const std::vector<gpu::Camera>& cameras,
                  const std::vector<render::RenderSettings>& per_view, MatrixRow& row) {
  std::vector<std::uint32_t> words;
  for (std::size_t k = 0; k < cameras.size(); ++k) {
    render::RenderSettings counting = per_view[k];
    counting.counters = true;
    renderer.set_settings(counting);
    const render::Frame f = renderer.render(cameras[k]);
    words.insert(words.end(), f.counters.begin(), f.counters.end());
  }
  const bench::CounterSummary work = bench::summarize_counters(words);
  row.queries_per_pixel = work.rows[bench::kQueriesStarted].mean;
  row.candidates_per_pixel = work.rows[bench::kCandidatesMet].mean;
}

// Time: the variant and the default alternately on the same frames (time_alternately).
void measure_time(render::Renderer& renderer, render::Renderer& default_renderer, const std::vector<gpu::Camera>& cameras,
                  const std::vector<render::RenderSettings>& per_view, unsigned rounds, MatrixRow& row) {
  std::vector<double> mine, theirs;
  for (unsigned round = 0; round < rounds; ++round)
    for (std::size_t k = 0; k < cameras.size(); ++k) {
      renderer.set_settings(per_view[k]);
      time_alternately(round, renderer, default_renderer, cameras[k], mine, theirs);
    }
  row.seconds_median = bench::frame_stats(mine).median;
  row.default_seconds_median = bench::frame_stats(theirs).median;
  row.time_ratio = row.seconds_median / row.default_seconds_median;
}

}  // namespace

std::vector<MatrixVariant> matrix_variants(const render::RenderSettings& base, const format::Package& package) {
  std::vector<MatrixVariant> v;
  // The knobs are the virtual traversal's: measured without the flat level, which has a row of its own.
  render::RenderSettings virtual_base = base;
  virtual_base.flatten_bytes = 0;
  const auto add = [&](std::string knob, std::string value, auto&& change, std::string note = {}) {
    MatrixVariant m;
    m.knob = std::move(knob), m.value = std::move(value), m.settings = virtual_base, m.note = std::move(note);
    change(m);
    v.push_back(std::move(m));
  };
  add("default", "3+rep, adaptive-overlap, exact, two-float-eye, no flat level, effects off", [](MatrixVariant& m) { m.is_default = true; });
  add("hierarchy", "3 (no repLAS)", [](MatrixVariant& m) { m.settings.replication_las = false; });
  add("hierarchy", "2 (atoms in tile BLAS)", [](MatrixVariant& m) {
    m.settings.two_level = true;
    m.scene.two_level_membranes = true;
  }, "membranes placed by the affine M1: an approximation");
  for (render::ShellMode shell : {render::ShellMode::adaptive, render::ShellMode::fixed_overlap, render::ShellMode::fixed})
    add("shell", render::to_string(shell), [&](MatrixVariant& m) { m.scene.shell = shell; },
        shell == render::ShellMode::fixed_overlap ? "" : "without overlap, molecules on triangle edges lose their outer part");
  add("prism test", "aabb only", [](MatrixVariant& m) { m.settings.exact_prism = false; });
  add("precision", "camera-relative float", [](MatrixVariant& m) { m.settings.precision = render::Precision::camera_relative; });
  add("precision", "world float", [](MatrixVariant& m) { m.settings.precision = render::Precision::world; });
  add("lod", "auto (beads under 1 px)", [](MatrixVariant& m) { m.settings.lod_pixels = 1; },
      "copies whose atoms span < 1 pixel drawn as their baked beads (residues, fragments of large ones); the oracle draws every atom");
  add("lod", "4 px", [](MatrixVariant& m) { m.settings.lod_pixels = 4; },
      "copies whose atoms span < 4 pixels drawn as beads");
  add("flat level", "auto (half the scene's memory)", [](MatrixVariant& m) { m.settings.flatten_bytes = render::kFlattenAuto; },
      "the membrane copies of the triangles in view as one TLAS instance each");
  render::EffectSettings effects = render::package_effects(package);
  effects.on = {};
  effects.time = 1.0;
  const bool animated = package.record_count(format::SectionKind::scene) == 1 &&
                        (package.records<format::SectionKind::scene>()[0].effect_flags & package_flag(EffectId::animation));
  // Every effect of the table alone; what the oracle does for it is the table's word.
  for (const EffectDeclaration& effect : effect_table()) {
    if (effect.id == EffectId::animation && !animated) continue;  // nothing moves: the row would repeat the default
    add("effect", std::string(effect.name), [&effects, id = effect.id](MatrixVariant& m) {
      m.settings.effects = effects;
      m.settings.effects.flag(id) = true;
    }, std::string(effect.oracle));
  }
  return v;
}

std::vector<MatrixVariant> select_matrix_knobs(std::vector<MatrixVariant> variants, const std::vector<std::string>& knobs,
                                               const std::string& option) {
  std::vector<std::string> table;  // the knobs beside the default, in the matrix's order
  for (const MatrixVariant& v : variants)
    if (!v.is_default && std::find(table.begin(), table.end(), v.knob) == table.end()) table.push_back(v.knob);
  std::set<std::string> wanted;
  for (std::string name : knobs) {
    const std::string asked = name;
    std::replace(name.begin(), name.end(), '-', ' ');
    if (std::find(table.begin(), table.end(), name) == table.end()) {
      std::string offered;
      for (const std::string& knob : table) offered += (offered.empty() ? "'" : ", '") + knob + "'";
      throw InputError(option, asked, "no such knob in the matrix (the default row is always there); its knobs: " + offered);
    }
    wanted.insert(name);
  }
  std::erase_if(variants, [&](const MatrixVariant& v) { return !v.is_default && !wanted.contains(v.knob); });
  return variants;
}

std::vector<MatrixRow> run_accuracy_matrix(const vk::Device& device, const format::Package& package,
                                           render::GpuScene& default_scene, const std::vector<gpu::Camera>& cameras,
                                           const std::vector<MatrixVariant>& variants, unsigned rounds,
                                           const std::vector<KnownOracleImage>& effect_free, const Progress& progress) {
  const MatrixVariant& reference = default_variant(variants, "run_accuracy_matrix");
  render::Renderer default_renderer(device, default_scene, reference.settings);
  for (const gpu::Camera& c : cameras) default_renderer.render(c);  // compiles the default pipeline
  OracleImages oracle_images(package, cameras, progress);
  for (const KnownOracleImage& known : effect_free) {
    if (known.view >= cameras.size() || known.hits.size() != std::size_t(cameras[known.view].size.x) * cameras[known.view].size.y)
      throw std::invalid_argument("run_accuracy_matrix: a known oracle image does not match its view");
    oracle_images.add(render::EffectSettings{}, known.view, known.hits);
  }

  std::vector<MatrixRow> rows;
  for (const MatrixVariant& v : variants) {
    if (progress) progress(v.knob + " = " + v.value);
    const bool own_scene = v.scene.shell != render::SceneOptions{}.shell || v.scene.two_level_membranes;
    std::unique_ptr<render::GpuScene> scene;
    if (own_scene) scene = std::make_unique<render::GpuScene>(device, package, v.scene);
    render::GpuScene& target = own_scene ? *scene : default_scene;
    render::Renderer renderer(device, target, v.settings);
    MatrixRow row;
    row.variant = v;
    row.device_bytes = target.report().memory.total();
    const std::vector<render::RenderSettings> per_view = per_view_settings(v.settings, cameras);
    measure_accuracy(renderer, target, cameras, per_view, oracle_images, row);
    measure_work(renderer, cameras, per_view, row);
    measure_time(renderer, default_renderer, cameras, per_view, rounds, row);
    rows.push_back(std::move(row));
  }
  return rows;
}

std::vector<LodFarRow> run_lod_far_views(const vk::Device& device, render::GpuScene& scene,
                                         const std::vector<LodFarView>& views, const std::vector<MatrixVariant>& variants,
                                         unsigned rounds, const Progress& progress) {
  render::Renderer full_renderer(device, scene, default_variant(variants, "run_lod_far_views").settings);
  std::vector<LodFarRow> rows;
  for (const MatrixVariant& v : variants) {
    if (v.knob != "lod") continue;
    render::Renderer renderer(device, scene, v.settings);
    for (const LodFarView& view : views) {
      if (progress) progress("lod " + v.value + ", " + view.name);
      LodFarRow row;
      row.view = view.name, row.value = v.value;
      const render::Frame reference = full_renderer.render(view.camera), coarse = renderer.render(view.camera);
      std::uint64_t changed = 0, coverage = 0;
      for (std::size_t p = 0; p < reference.hits.size(); ++p) {
        const gpu::PixelHit& a = reference.hits[p];
        const gpu::PixelHit& b = coarse.hits[p];
        coverage += (a.atom == gpu::kNoHit) != (b.atom == gpu::kNoHit);
        changed += a.atom != b.atom || a.copy_number_lo != b.copy_number_lo || a.copy_number_hi != b.copy_number_hi ||
                   a.depth != b.depth;
      }
      row.pixels = reference.hits.size();
      row.ids_changed_percent = 100.0 * double(changed) / double(row.pixels);
      row.coverage_changed_percent = 100.0 * double(coverage) / double(row.pixels);
      std::vector<double> mine, theirs;
      for (unsigned round = 0; round < rounds; ++round)
        time_alternately(round, renderer, full_renderer, view.camera, mine, theirs);
      row.seconds_median = bench::frame_stats(mine).median;
      row.full_seconds_median = bench::frame_stats(theirs).median;
      row.time_ratio = row.seconds_median / row.full_seconds_median;
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

nlohmann::json to_json(const std::vector<LodFarRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const LodFarRow& r : rows)
    out.push_back({{"view", r.view},
                   {"lod", r.value},
                   {"time_ratio", r.time_ratio},
                   {"frame_seconds_median", r.seconds_median},
                   {"full_detail_frame_seconds_median", r.full_seconds_median},
                   {"ids_changed_percent", r.ids_changed_percent},
                   {"coverage_changed_percent", r.coverage_changed_percent},
                   {"pixels", r.pixels}});
  return out;
}

std::string lod_far_markdown(const std::vector<LodFarRow>& rows) {
  std::string md =
      "\nLevel of detail on far views, against the full-detail frame of the same renderer (the oracle cannot resolve them)\n\n"
      "| view | lod | frame time vs full detail | pixels changed (id or depth) | silhouette changed |\n|---|---|---|---|---|\n";
  for (const LodFarRow& r : rows) {
    char line[512];
    std::snprintf(line, sizeof line, "| %s | %s | %.2f× | %.2f %% | %.2f %% |\n", r.view.c_str(), r.value.c_str(), r.time_ratio,
                  r.ids_changed_percent, r.coverage_changed_percent);
    md += line;
  }
  return md;
}

nlohmann::json to_json(const std::vector<MatrixRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const MatrixRow& r : rows)
    out.push_back({{"knob", r.variant.knob},
                   {"value", r.variant.value},
                   {"default", r.variant.is_default},
                   {"time_ratio", r.time_ratio},
                   {"frame_seconds_median", r.seconds_median},
                   {"default_frame_seconds_median", r.default_seconds_median},
                   {"wrong_pixels_percent", r.wrong_percent},
                   {"pixels", r.pixels},
                   {"device_memory_bytes", r.device_bytes},
                   {"queries_per_pixel", r.queries_per_pixel},
                   {"candidates_per_pixel", r.candidates_per_pixel},
                   {"note", r.variant.note}});
  return out;
}

std::string matrix_markdown(const std::vector<MatrixRow>& rows, const std::string& heading) {
  std::string md = heading +
                   "\n\n| knob | value | frame time vs default | pixels wrong vs oracle | device memory | queries / pixel | "
                   "candidates / pixel | note |\n|---|---|---|---|---|---|---|---|\n";
  for (const MatrixRow& r : rows) {
    char line[512];
    std::snprintf(line, sizeof line, "| %s | %s | %.2f× | %.3f %% | %.1f MB | %.1f | %.1f | %s |\n", r.variant.knob.c_str(),
                  r.variant.value.c_str(), r.time_ratio, r.wrong_percent, double(r.device_bytes) / 1e6, r.queries_per_pixel,
                  r.candidates_per_pixel, r.variant.note.c_str());
    md += line;
  }
  return md;
}

bench::PlotSpec matrix_plot(const std::vector<MatrixRow>& rows, const std::string& title) {
  bench::PlotSpec spec;
  spec.title = title;
  spec.x_label = "frame time / default";
  spec.y_label = "% pixels differing from the oracle";
  std::map<std::string, bench::PlotSeries> by_knob;
  std::vector<std::string> order;
  for (const MatrixRow& r : rows) {
    if (!by_knob.count(r.variant.knob)) order.push_back(r.variant.knob), by_knob[r.variant.knob].name = r.variant.knob;
    by_knob[r.variant.knob].points.push_back({r.time_ratio, r.wrong_percent, r.variant.is_default ? "default" : r.variant.value});
  }
  for (const std::string& k : order) spec.series.push_back(by_knob[k]);
  return spec;
}

}  // namespace nano::session
