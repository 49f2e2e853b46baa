#pragma once
// The accuracy/time matrix of `nanoview bench --matrix` (DESIGN.md "Knobs that trade accuracy for
// time"): every knob value against the default on the same frames in one run — frame time as a
// ratio to the default measured alternately with it, and the share of pixels that differ from the
// CPU oracle (explicit instancing with the same effects).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "format/package.hpp"
#include "runtime/bench/svg_plot.hpp"
#include "runtime/render/camera_spec.hpp"
#include "runtime/render/gpu_scene.hpp"
#include "runtime/render/renderer.hpp"
#include "runtime/vk/device.hpp"

namespace nano::session {

struct MatrixVariant {
  std::string knob, value;
  render::SceneOptions scene;  // a value that needs other acceleration structures gets its own GpuScene
  render::RenderSettings settings;
  bool is_default = false;
  std::string note;  // what the error column means for it, when not the obvious
};

// The default first, then hierarchy, shell, prism test, precision and each effect. `base` holds the
// default knobs. Clipping gets one plane per view, 400 Å ahead of its eye, keeping the near side.
std::vector<MatrixVariant> matrix_variants(const render::RenderSettings& base, const format::Package& package);

// The default row and the rows of the knobs named (a knob's name as the table prints it, or with
// '-' for its spaces: "flat-level"), in the matrix's order: a matrix of what one is tuning, minutes
// shorter than every knob on a large scene. Throws InputError (key `option`) for a name no row has,
// listing the knobs there are.
std::vector<MatrixVariant> select_matrix_knobs(std::vector<MatrixVariant> variants, const std::vector<std::string>& knobs,
                                               const std::string& option);

struct MatrixRow {
  MatrixVariant variant;
  double seconds_median = 0;          // per frame, over cameras × rounds
  double default_seconds_median = 0;  // the default's, measured alternately with this variant
  double time_ratio = 1;              // seconds_median / default_seconds_median
  double wrong_percent = 0;           // pixels not agreeing with the oracle (oracle::compare_images)
  std::uint64_t pixels = 0;
  std::uint64_t device_bytes = 0;     // device memory of the scene the variant renders
  double queries_per_pixel = 0;       // ray queries started, mean over the views' pixels (counters)
  double candidates_per_pixel = 0;    // candidates met at every level, likewise
};

using Progress = std::function<void(const std::string&)>;

// An oracle image the caller already made: of cameras[view], every effect off.
struct KnownOracleImage {
  std::size_t view = 0;
  std::vector<gpu::PixelHit> hits;
};

// Renders every camera with every variant (after one warm-up frame each), `rounds` times, and
// compares one frame per camera with the oracle. `default_scene` must hold the default scene options.
// The oracle images in `effect_free` are used as they are, not made again.
std::vector<MatrixRow> run_accuracy_matrix(const vk::Device& device, const format::Package& package,
                                           render::GpuScene& default_scene, const std::vector<gpu::Camera>& cameras,
                                           const std::vector<MatrixVariant>& variants, unsigned rounds,
                                           const std::vector<KnownOracleImage>& effect_free = {}, const Progress& progress = {});

// The level of detail where it acts: far views (a whole cell, a whole scene) that the CPU oracle
// cannot resolve, so each lod variant is compared with the full-detail frame of the same renderer
// (which verify holds to the oracle on the near views) and timed alternately with it.
struct LodFarView {
  std::string name;
  gpu::Camera camera;
};
struct LodFarRow {
  std::string view, value;
  double seconds_median = 0, full_seconds_median = 0, time_ratio = 1;
  double ids_changed_percent = 0;       // pixels naming another atom or copy, or another depth, than full detail
  double coverage_changed_percent = 0;  // pixels that turned from background to molecule or back: the silhouette
  std::uint64_t pixels = 0;
};
// `variants`: the matrix's rows; those of knob "lod" are measured against the default's settings.
std::vector<LodFarRow> run_lod_far_views(const vk::Device& device, render::GpuScene& scene,
                                         const std::vector<LodFarView>& views, const std::vector<MatrixVariant>& variants,
                                         unsigned rounds, const Progress& progress = {});
nlohmann::json to_json(const std::vector<LodFarRow>& rows);
std::string lod_far_markdown(const std::vector<LodFarRow>& rows);

nlohmann::json to_json(const std::vector<MatrixRow>& rows);
std::string matrix_markdown(const std::vector<MatrixRow>& rows, const std::string& heading);
bench::PlotSpec matrix_plot(const std::vector<MatrixRow>& rows, const std::string& title);

}  // namespace nano::session
