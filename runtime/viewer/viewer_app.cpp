#include "runtime/viewer/viewer_app.hpp"

#include <algorithm>
#include <chrono>
#include <thread>
#include <cstdlib>
#include <optional>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <ctime>
#include <iostream>
#include <memory>
#include <span>
#include <stdexcept>
#include <vector>

#include <imgui.h>

#include "common/error.hpp"
#include "runtime/render/camera_path.hpp"
#include "runtime/render/camera_spec.hpp"
#include "runtime/render/image_io.hpp"
#include "runtime/render/pick_info.hpp"
#include "runtime/viewer/camera_controller.hpp"
#include "runtime/viewer/camera_input.hpp"
#include "runtime/viewer/overlay.hpp"
#include "runtime/viewer/panel.hpp"
#include "runtime/viewer/path_recording.hpp"
#include "runtime/viewer/presenter.hpp"
#include "runtime/viewer/progressive.hpp"
#include "runtime/viewer/script.hpp"
#include "runtime/viewer/script_runner.hpp"
#include "runtime/viewer/viewer_state.hpp"
#include "runtime/viewer/window.hpp"

namespace nano::viewer {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::pair<std::uint32_t, std::uint32_t> kDefaultSize{960, 720};
// A frame is traced in parts of about this many seconds, input and presenting in between, so the
// window answers at ≥ 30 Hz whatever the whole frame costs (one queue suffices: nothing waits on
// more than one part).
constexpr double kPartSeconds = 0.015;

std::optional<double> centre_depth(const render::Frame& frame) {
  if (frame.hits.empty()) return std::nullopt;
  const gpu::PixelHit& hit = frame.hits[std::size_t(frame.height / 2) * frame.width + frame.width / 2];
  if (hit.atom == gpu::kNoHit || !std::isfinite(hit.depth)) return std::nullopt;
  return double(hit.depth);
}

std::string timestamped_name() {
  const std::time_t now = std::time(nullptr);
  char name[64];
  std::strftime(name, sizeof name, "nanoview-%Y%m%d-%H%M%S.png", std::localtime(&now));
  return name;
}

class Viewer final : public ScriptHost {
public:
  Viewer(const ViewerOptions& options, render::RenderSettings settings, std::optional<Script> script,
         std::optional<render::CameraPath> path)
      : options_(options),
        script_(std::move(script)),
        window_(options.size.value_or(kDefaultSize).first, options.size.value_or(kDefaultSize).second,
                "nanoview — " + options.package),
        session_(options.package, options.variant.scene_options(),
                 session::PresentationOptions{window_.required_instance_extensions(), {VK_KHR_SWAPCHAIN_EXTENSION_NAME},
                                           [this](VkInstance instance) { return window_.create_surface(instance); }}),
        bounds_(scene_bounds(session_.package)),
        hideable_(placement::hideable_names(session_.package)),
        state_(CameraController(session::camera_option(session_.package, options.camera), bounds_.radius()), settings) {
    settings.effects = options.effects.settings(session_.package);
    state_.settings = settings;
    state_.ao_samples = std::max(options.ao_samples, 1u);
    if (path) {
      state_.path.path = std::move(*path);
      state_.path.file = options.path;  // "Save path" writes the edited path back where it came from
    }
    if (script_) {
      check_show_names(*script_, hideable_);
      fixed_size_ = options.size.value_or(kDefaultSize);
    }
    presenter_ = std::make_unique<Presenter>(session_.device, session_.surface.handle(), window_);
    overlay_ = std::make_unique<Overlay>(window_, session_.instance.handle(), session_.device, *presenter_);
    presenter_->on_recreate = [this](std::uint32_t count) { overlay_->set_min_image_count(count); };
    renderer_ = std::make_unique<render::Renderer>(session_.device, *session_.scene, state_.settings);
  }

  ~Viewer() override { shutdown(); }

  int run() {
    if (script_) {
      for (const ScriptCommand& command : script_->commands) {
        window_.poll_events();
        if (window_.should_close()) {
          std::fprintf(stderr, "%s: the window was closed; the script stopped before line %zu\n", script_->file.c_str(),
                       command.line);
          return 1;
        }
        if (!run_command(command, script_->file, *this, std::cout)) return 0;  // quit
      }
      if (!options_.stay) return 0;
      fixed_size_.reset();  // from here the window's size rules, as in interactive use
    }
    interactive_loop();
    return 0;
  }

  // Destroys what lives on the device before the session, and reports the validation layer's
  // findings; throws when it found errors.
  void finish() {
    shutdown();
    if (session_.instance.validation_enabled())
      std::fprintf(stderr, "view: validation layer: %u error(s), %u warning(s)\n", session_.instance.validation_errors(),
                   session_.instance.validation_warnings());
    std::fprintf(stderr, "view: %llu frame(s) rendered, %llu presented\n", (unsigned long long)rendered_,
                 (unsigned long long)presented_);
    if (session_.validation_errors() != 0)
      throw std::runtime_error("the Vulkan validation layer reported " + std::to_string(session_.validation_errors()) +
                               " error(s)");
  }

  // ScriptHost
  ViewerState& state() override { return state_; }

  void render_frames(std::uint32_t count) override {
    for (std::uint32_t i = 0; i < count; ++i) {
      window_.poll_events();
      if (window_.should_close()) throw std::invalid_argument("the window was closed");
      render_full();
      present_with_panel();
    }
  }

  const render::Frame& current_frame() override {
    if (!full_is_current()) render_frames(1);
    return full_;
  }

  std::span<const std::uint32_t> current_image() override {
    (void)current_frame();
    return accumulator_.result();
  }

  void resize(std::uint32_t width, std::uint32_t height) override {
    if (fixed_size_) fixed_size_ = {width, height};
    window_.resize(width, height);
  }

  nlohmann::json describe(const gpu::PixelHit& hit) override { return render::describe_hit(session_.package, hit); }

private:
  std::pair<std::uint32_t, std::uint32_t> render_size() const {
    if (fixed_size_) return *fixed_size_;
    return window_.framebuffer_size();
  }

  bool full_is_current() const {
    const auto [w, h] = render_size();
    return full_version_ == state_.version && full_.width == w && full_.height == h && !full_.hits.empty();
  }

  bool wants_more_samples() const {
    return state_.settings.effects.flag(EffectId::ambient_occlusion) && accumulator_.count() < state_.ao_samples;
  }

  // A frame of the current state being made: at 1/scale per axis of the window's `size` (scale 1:
  // the full frame, AO sample `sample`), traced part by part between polls of the window.
  struct Job {
    std::uint32_t scale = 1, sample = 0;
    std::pair<std::uint32_t, std::uint32_t> size;
    std::uint64_t version = 0;
    render::RenderSettings settings;
  };

  Job make_job(std::uint32_t scale) const {
    Job job;
    job.scale = scale;
    job.size = render_size();
    job.version = state_.version;
    if (scale == 1) job.sample = full_is_current() && state_.settings.effects.flag(EffectId::ambient_occlusion) ? accumulator_.count() : 0;
    job.settings = state_.settings;
    job.settings.focus_distance = render::focus_distance_for(state_.camera.camera());
    job.settings.effects.sample_index = job.sample;
    // While the view moves, the flat level grows by at most 4,000 new copies a frame (~30 ms of
    // enumeration on the CPU); the full frame at rest takes the whole choice, so it is the frame
    // `nanoview render` makes.
    if (scale != 1) job.settings.flatten_new_copies = 4000;
    return job;
  }

  gpu::Camera job_camera(const Job& job) const {
    return state_.camera.camera().to_gpu(reduced_extent(job.size.first, job.scale), reduced_extent(job.size.second, job.scale));
  }

  // Takes a finished frame of `job`: the full frame (a new average when the state changed,
  // otherwise one more AO sample into it) or a reduced one the presenter stretches over the window.
  void adopt(const Job& job, render::Frame frame) {
    ++rendered_;
    const std::uint64_t pixels = std::uint64_t(frame.width) * frame.height;
    state_.stats.seconds = frame.seconds;
    state_.stats.width = frame.width, state_.stats.height = frame.height;
    state_.stats.rays_per_second =
        frame.seconds > 0 ? double(render::Renderer::rays_per_frame(job.settings, pixels)) / frame.seconds : 0;
    seconds_per_pixel_ = frame.seconds / double(pixels);
    state_.camera.set_focus_depth(centre_depth(frame));
    if (job.scale == 1) {
      if (job.sample == 0) accumulator_.reset();
      full_ = std::move(frame);
      full_version_ = job.version;
      accumulator_.add(full_.rgba, full_.width, full_.height);
      state_.stats.scale = 1;
      state_.stats.samples = accumulator_.count();
      shown_ = &full_;
    } else {
      reduced_ = std::move(frame);
      reduced_version_ = job.version;
      reduced_scale_ = job.scale;
      reduced_size_ = job.size;
      state_.stats.scale = job.scale;
      state_.stats.samples = 1;
      shown_ = &reduced_;
    }
  }

  // One whole frame now (scripts, screenshots); abandons a banded frame in progress.
  void render_now(std::uint32_t scale) {
    job_.reset();
    const Job job = make_job(scale);
    renderer_->set_settings(job.settings);
    adopt(job, renderer_->render(job_camera(job)));
  }

  void render_full() { render_now(1); }

  // Starts a banded frame of the current state at 1/scale (nothing traced yet) — unless the pipeline
  // its settings select is not built yet: then it is built on a worker thread (Renderer::prepare),
  // the window keeps what it shows and input goes on; a later call starts the frame once it is ready.
  void start_job(std::uint32_t scale) {
    const Job next = make_job(scale);
    if (!renderer_->ready(next.settings)) {
      const std::string name = render::Renderer::variant_name(next.settings);
      if (compiling_ != name) {
        renderer_->prepare(next.settings);
        compiling_ = name;
        std::fprintf(stderr, "view: compiling the pipeline %s on a worker thread at %.3f\n", name.c_str(), wall_seconds());
      }
      state_.compiling = "compiling " + name + "… " + std::to_string(int(renderer_->preparing_seconds(next.settings))) + " s";
      return;
    }
    if (!compiling_.empty()) {
      std::fprintf(stderr, "view: pipeline %s ready at %.3f\n", compiling_.c_str(), wall_seconds());
      compiling_.clear();
      state_.compiling.clear();
    }
    job_ = next;
    part_seconds_per_pixel_ = 0;
    renderer_->set_settings(job_->settings);
    renderer_->begin(job_camera(*job_));
    if (input_log_ && scale == 1)
      std::fprintf(stderr, "view: full %ux%u frame begun at %.3f (%s)\n", job_->size.first, job_->size.second, wall_seconds(),
                   render::Renderer::variant_name(job_->settings).c_str());
  }

  // Traces the next part of the frame in progress, sized to kPartSeconds by the dearest cost per
  // pixel met so far in this frame or the last frame's average (cost varies a lot over an image:
  // a part sized by a cheap background part would be far too long over the scene); true when it
  // completed the frame (then adopted).
  bool advance_job() {
    const double cost = std::max(part_seconds_per_pixel_, seconds_per_pixel_);
    const std::uint64_t budget = cost > 0 ? std::uint64_t(std::clamp(kPartSeconds / cost, 1.0, 1e9))
                                          : ~std::uint64_t(0);  // nothing measured yet: the (coarse first) frame whole
    const auto start = Clock::now();
    const render::Renderer::Part part = renderer_->trace_part(budget);
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    part_seconds_per_pixel_ = std::max(part_seconds_per_pixel_, seconds / double(std::max<std::uint64_t>(part.pixels, 1)));
    if (!part.complete) return false;
    const Job job = *job_;
    job_.reset();
    part_seconds_per_pixel_ = 0;
    adopt(job, renderer_->finish());
    if (input_log_ && job.scale == 1) std::fprintf(stderr, "view: full frame finished at %.3f\n", wall_seconds());
    return true;
  }

  static double wall_seconds() {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  }
  // A time of the viewer's clock on wall_seconds()'s scale (the log's).
  static double wall_seconds(Clock::time_point t) {
    return wall_seconds() - std::chrono::duration<double>(Clock::now() - t).count();
  }

  // NANO_VIEW_INPUT_LOG: each key handled, once the window has presented a frame made after it
  // (its overlay shows the key's effect), with the viewer's own times: the latest the key can have
  // waited since (Window::KeyTimes::queued_after), its callback, its handling and the present.
  void log_presented_keys() {
    const auto now = Clock::now();
    for (const HandledKey& k : unpresented_keys_)
      std::fprintf(stderr,
                   "view: key %d presented %.1f ms after it was queued at the earliest (%llu window frame(s) later): "
                   "queued after %.3f, received %.3f, handled %.3f, presented %.3f\n",
                   k.key, 1000 * std::chrono::duration<double>(now - k.times.queued_after).count(),
                   (unsigned long long)(presented_ - k.presented_before), wall_seconds(k.times.queued_after),
                   wall_seconds(k.times.received), wall_seconds(k.handled), wall_seconds(now));
    unpresented_keys_.clear();
  }

  // At rest: the scale of the next refinement step towards the full-resolution frame of the
  // current state (coarse steps first, so something of a new state shows at once).
  std::uint32_t refinement_scale() const {
    const auto [w, h] = render_size();
    const bool reduced_current =
        shown_ == &reduced_ && reduced_version_ == state_.version && reduced_size_ == std::pair(w, h);
    return full_is_current() ? 1 : rest_scale(reduced_current ? reduced_scale_ : 0, seconds_per_pixel_, w, h, state_.rest_step_budget);
  }

  bool present() {
    if (shown_ == nullptr) return false;
    // The full frame shows its accumulated AO samples; a reduced frame shows itself.
    const std::span<const std::uint32_t> image =
        shown_ == &full_ ? std::span<const std::uint32_t>(accumulator_.result()) : std::span<const std::uint32_t>(reduced_.rgba);
    const bool shown = presenter_->present(image, shown_->width, shown_->height,
                                           [this](VkCommandBuffer commands) { overlay_->record(commands); });
    presented_ += shown;
    if (shown) log_presented_keys();
    return shown;
  }

  void present_with_panel() {
    overlay_->begin_frame();
    draw_panel(state_, panel_context());
    overlay_->end_frame();
    present();
  }

  PanelContext panel_context() const {
    return PanelContext{&session_.scene->report(), bounds_, fixed_size_.has_value(), hideable_};
  }

  void pick(double x, double y) {
    if (shown_ == nullptr) return;
    const ImVec2 window = ImGui::GetIO().DisplaySize;
    if (window.x <= 0 || window.y <= 0) return;
    // The shown frame is stretched over the whole window, whatever resolution it has.
    const auto px = std::uint32_t(std::clamp(x / window.x * shown_->width, 0.0, shown_->width - 1.0));
    const auto py = std::uint32_t(std::clamp(y / window.y * shown_->height, 0.0, shown_->height - 1.0));
    nlohmann::json j = describe(shown_->hits[std::size_t(py) * shown_->width + px]);
    j["x"] = px;
    j["y"] = py;
    std::cout << j.dump() << std::endl;
    state_.last_pick = std::move(j);
  }

  void screenshot() {
    if (!full_is_current()) render_full();
    const std::string path = timestamped_name();
    try {
      render::write_png(path, full_.width, full_.height, accumulator_.result());
      render::write_ids(ids_path_for(path), full_.width, full_.height, full_.hits);
      state_.status = "wrote " + path + " (and .ids)";
    } catch (const std::exception& e) {
      state_.status = std::string("screenshot failed: ") + e.what();
    }
  }

  // Every new status line (screenshots, keyframes, path files, refused settings) also goes to
  // stderr: the panel shows only the last, and a session log should keep them all.
  void log_status() {
    if (state_.status == logged_status_) return;
    logged_status_ = state_.status;
    if (!logged_status_.empty()) std::fprintf(stderr, "view: %s\n", logged_status_.c_str());
  }

  // Whether the loop has something to trace, show or play; at rest it sleeps until input instead.
  bool busy(bool active) const {
    return active || job_ || shown_ == &reduced_ || shown_ == nullptr || !full_is_current() || wants_more_samples() ||
           state_.playing || state_.path.play_time;
  }

  // At rest with every sample in, sleep until something happens: no frame, no CPU.
  // While a pipeline builds on a worker thread there is nothing to trace: wait for input a little
  // rather than spin on the core the compiler needs, and look at the build ~20 times a second.
  void wait_for_events(bool has_work) {
    if (!compiling_.empty()) {
      // (Under Xvfb the wait returns at once, events or not: a short sleep keeps the core free.)
      std::this_thread::sleep_for(std::chrono::milliseconds(15));
      window_.wait_events(0.035);
    } else if (has_work) {
      window_.poll_events();
    } else {
      window_.wait_events(0.5);
    }
  }

  void log_handled_keys(const InputResult& input) {
    if (!input_log_) return;
    const std::vector<Window::KeyTimes>& times = window_.last_key_times();
    for (std::size_t k = 0; k < input.keys.size(); ++k) {
      std::fprintf(stderr, "view: key %d handled at %.3f\n", input.keys[k], wall_seconds());
      if (k < times.size()) unpresented_keys_.push_back({input.keys[k], times[k], Clock::now(), presented_});
    }
  }

  // The camera, playback and key toggles of this iteration's input, and the time it moves on.
  void apply_input(const InputResult& input, double dt) {
    if (input.camera_moved) {
      state_.touch();
      if (state_.path.play_time) {  // the user takes the camera back
        stop_playback(state_);
        state_.status = "path playback stopped by camera input";
        log_status();
      }
    }
    // Advanced before K, L and the panel act: a playback they start shows time 0 first instead of
    // jumping ahead by however long the previous (perhaps full-resolution) frame took.
    advance_playback(state_, dt);
    log_status();
    // K and L can both arrive during one long frame: each outcome is logged.
    if (input.add_keyframe) {
      record_keyframe(state_);
      log_status();
    }
    if (input.toggle_path) {
      toggle_playback(state_);
      log_status();
    }
    if (input.toggle_ambient_occlusion) {
      state_.settings.effects.flag(EffectId::ambient_occlusion) = !state_.settings.effects.flag(EffectId::ambient_occlusion);
      state_.touch();
    }
    if (state_.playing && !state_.path.play_time) {  // while a path plays, it drives the time
      state_.settings.effects.time += dt * state_.play_speed;
      state_.touch();
    }
  }

  // Draws the panel into the overlay's frame. True while a slider is dragged: that is motion too,
  // previewed at reduced resolution.
  bool run_panel() {
    const std::uint64_t before_panel = state_.version;
    const Camera camera_before_panel = state_.camera.camera();
    draw_panel(state_, panel_context());
    if (state_.path.play_time && camera_before_panel != state_.camera.camera()) {
      stop_playback(state_);  // an edit in the camera section is camera input too
      state_.status = "path playback stopped by a camera edit";
    }
    log_status();
    return ImGui::IsAnyItemActive() && state_.version != before_panel;
  }

  // Takes a requested screenshot, then starts, keeps or drops the frame in progress and traces its
  // next part. `shown_reduced`: the window showed a reduced frame when this iteration began.
  void advance_frames(bool screenshot_key, bool moving, bool shown_reduced) {
    try {
      if (screenshot_key || state_.screenshot_requested) {
        state_.screenshot_requested = false;
        screenshot();
      }
      // A frame of a state that has changed since it began is dropped, except a reduced one
      // while moving (each is cheap and shows the motion; dropping them could show nothing).
      if (job_ && job_->version != state_.version && !(moving && job_->scale > 1)) job_.reset();
      if (job_ && job_->size != render_size()) job_.reset();
      if (!job_) {
        const auto [rw, rh] = render_size();
        if (moving) start_job(motion_scale(seconds_per_pixel_, rw, rh, state_.motion_budget));
        else if (shown_reduced || shown_ == nullptr || !full_is_current() || wants_more_samples()) start_job(refinement_scale());
      }
      if (job_) advance_job();
    } catch (const InputError& e) {
      // Settings the renderer refuses (e.g. an effect the two-level path lacks): say so, keep going.
      state_.status = e.what();
      state_.touch();
    }
    log_status();
  }

  // While a frame is traced in parts, the window (panel, overlay) is presented at ~60 Hz, not after
  // every part; camera motion is shown at once.
  void present_when_due(bool camera_moved) {
    const auto presenting = Clock::now();
    if (!job_ || camera_moved || std::chrono::duration<double>(presenting - last_present_).count() >= 1.0 / 60) {
      present();
      last_present_ = presenting;
    }
  }

  void interactive_loop() {
    auto last = Clock::now();
    bool active = false;
    while (!window_.should_close()) {
      const bool shown_reduced = shown_ == &reduced_;
      wait_for_events(busy(active));
      const auto now = Clock::now();
      const double dt = std::chrono::duration<double>(now - last).count();
      last = now;
      const auto [w, h] = window_.framebuffer_size();
      if (w == 0 || h == 0) {  // minimised: nothing to render or show until it comes back
        window_.wait_events(0.5);
        continue;
      }

      overlay_->begin_frame();
      const InputResult input = handle_camera_input(window_, state_.camera, dt);
      log_handled_keys(input);
      apply_input(input, dt);
      const bool panel_dragging = run_panel();
      overlay_->end_frame();
      active = input.dragging || ImGui::IsAnyItemActive();

      if (input.click) pick(input.click->first, input.click->second);
      const bool moving = input.camera_moved || state_.playing || panel_dragging || state_.path.play_time.has_value();
      advance_frames(input.screenshot, moving, shown_reduced);
      present_when_due(input.camera_moved);
    }
  }

  void shutdown() {
    job_.reset();
    renderer_.reset();
    overlay_.reset();
    presenter_.reset();
  }

  ViewerOptions options_;
  std::optional<Script> script_;
  Window window_;
  session::RenderSession session_;
  Bounds bounds_;
  std::vector<placement::HideableName> hideable_;  // what the panel's "show" switches and scripts may name
  ViewerState state_;
  std::unique_ptr<Presenter> presenter_;
  std::unique_ptr<Overlay> overlay_;
  std::unique_ptr<render::Renderer> renderer_;
  std::optional<std::pair<std::uint32_t, std::uint32_t>> fixed_size_;  // scripted: exactly this render size

  render::Frame full_, reduced_;
  std::uint64_t full_version_ = ~std::uint64_t(0);
  std::uint64_t reduced_version_ = ~std::uint64_t(0);  // the state reduced_ shows, at reduced_scale_
  std::uint32_t reduced_scale_ = 1;
  std::pair<std::uint32_t, std::uint32_t> reduced_size_{0, 0};  // the full size it was reduced from
  Accumulator accumulator_;
  const render::Frame* shown_ = nullptr;  // what the window shows (its hits answer clicks)
  double seconds_per_pixel_ = 0;
  std::optional<Job> job_;  // the frame in progress, traced in parts
  double part_seconds_per_pixel_ = 0;  // the dearest cost per pixel of its parts so far
  Clock::time_point last_present_{};
  const bool input_log_ = std::getenv("NANO_VIEW_INPUT_LOG") != nullptr;  // tests: input and full-frame times
  struct HandledKey {
    int key;
    Window::KeyTimes times;
    Clock::time_point handled;
    std::uint64_t presented_before;  // presented_ when it was handled
  };
  std::vector<HandledKey> unpresented_keys_;  // handled, not yet presented (only with input_log_)
  std::string logged_status_;
  std::string compiling_;  // the pipeline being built on a worker thread (its variant name), if any
  std::uint64_t rendered_ = 0, presented_ = 0;
};

}  // namespace

int run_viewer(const ViewerOptions& options) {
  // Everything that can be checked without a window is checked first (the package itself is
  // validated by RenderSession, which needs the window's surface extensions).
  if (!std::filesystem::is_regular_file(options.package))
    throw InputError(options.package, "", "no such package file");
  const render::RenderSettings settings = options.variant.render_settings();
  (void)options.variant.scene_options();
  std::optional<Script> script;
  if (!options.script.empty()) script = load_script(options.script);
  std::optional<render::CameraPath> path;
  if (!options.path.empty()) path = render::read_camera_path(options.path);
  Viewer viewer(options, settings, std::move(script), std::move(path));
  const int status = viewer.run();
  viewer.finish();
  return status;
}

}  // namespace nano::viewer
