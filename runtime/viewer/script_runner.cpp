#include "runtime/viewer/script_runner.hpp"

#include <filesystem>
#include <stdexcept>

#include "common/error.hpp"
#include "runtime/render/camera_path.hpp"
#include "runtime/render/camera_spec.hpp"
#include "runtime/render/effects.hpp"
#include "runtime/render/image_io.hpp"
#include "runtime/viewer/path_recording.hpp"

namespace nano::viewer {
namespace {

using K = ScriptCommand::Kind;

void add_clip_plane(render::EffectSettings& effects, const glm::dvec4& plane, const InputSource& line) {
  if (effects.clipping.planes.size() >= render::kMaxClipPlanes)
    line.fail("at most " + std::to_string(render::kMaxClipPlanes) + " clip planes (the scene's included); 'clip off' removes them");
  effects.clipping.planes.push_back(plane);
  effects.flag(EffectId::clipping) = true;
}

// A command that changes what the frame shows (camera, clipping, effects, shown names, time, size).
void change_view(const ScriptCommand& c, const InputSource& line, ScriptHost& host) {
  ViewerState& s = host.state();
  render::EffectSettings& effects = s.settings.effects;
  switch (c.kind) {
    case K::camera: s.camera.set_camera(render::parse_camera(c.text, s.camera.camera(), line)); break;
    case K::clip_plane: add_clip_plane(effects, c.plane, line); break;
    case K::clip_box:
      effects.clipping.box = c.box;
      effects.flag(EffectId::clipping) = true;
      break;
    case K::clip_off:
      effects.clipping = {};
      effects.flag(EffectId::clipping) = false;
      break;
    case K::effect: render::set_effect(effects, c.text, c.on, line); break;
    case K::preset: render::apply_preset(effects, c.text, line); break;
    case K::show: render::set_shown(s.settings, c.text, c.on); break;
    case K::time: effects.time = c.seconds; break;
    case K::size: host.resize(c.x, c.y); break;
    default: return;
  }
  s.touch();
}

void pick_pixel(const ScriptCommand& c, const InputSource& line, ScriptHost& host, std::ostream& out) {
  const render::Frame& frame = host.current_frame();
  if (c.x >= frame.width || c.y >= frame.height)
    line.fail("pixel (" + std::to_string(c.x) + ", " + std::to_string(c.y) + ") lies outside the " + std::to_string(frame.width) +
              "x" + std::to_string(frame.height) + " frame");
  nlohmann::json j = host.describe(frame.hits[std::size_t(c.y) * frame.width + c.x]);
  j["x"] = c.x;
  j["y"] = c.y;
  out << j.dump() << '\n' << std::flush;  // one line per pick: scripts parse stdout line by line
  host.state().last_pick = std::move(j);
}

void write_screenshot(const std::string& path, ScriptHost& host) {
  const render::Frame& frame = host.current_frame();
  const auto image = host.current_image();
  render::write_png(path, frame.width, frame.height, image);
  render::write_ids(ids_path_for(path), frame.width, frame.height, frame.hits);
  host.state().status = "screenshot " + path;
}

// keyframe and the path commands: only the path changes, not what the frame shows (no touch()).
void run_path_command(const ScriptCommand& c, const InputSource& line, ScriptHost& host) {
  ViewerState& s = host.state();
  switch (c.kind) {
    case K::keyframe: add_keyframe(s.path.path, s.camera.camera(), c.seconds, line); break;
    case K::path_save:
      if (s.path.path.keyframes.empty()) line.fail("no keyframes to save ('keyframe SECONDS' adds one)");
      render::write_camera_path(c.text, s.path.path);
      s.status = "saved path " + c.text;
      break;
    case K::path_load:
      s.path.path = render::read_camera_path(c.text);
      stop_playback(s);
      break;
    case K::path_clear:
      stop_playback(s);
      s.path.path.keyframes.clear();
      break;
    case K::path_frame: show_path_at(s, path_frame_time(s.path.path, c.first, line)); break;
    case K::path_play:
      (void)path_frame_time(s.path.path, c.last, line);  // a range past the end fails before any frame
      for (std::uint32_t k = c.first; k <= c.last; ++k) {
        show_path_at(s, path_frame_time(s.path.path, k, line));
        host.render_frames(1);
      }
      break;
    default: break;
  }
}

void execute(const ScriptCommand& c, const InputSource& line, ScriptHost& host, std::ostream& out) {
  switch (c.kind) {
    case K::camera:
    case K::clip_plane:
    case K::clip_box:
    case K::clip_off:
    case K::effect:
    case K::preset:
    case K::show:
    case K::time:
    case K::size: change_view(c, line, host); break;
    case K::wait: host.render_frames(c.count); break;
    case K::pick: pick_pixel(c, line, host, out); break;
    case K::screenshot: write_screenshot(c.text, host); break;
    case K::keyframe:
    case K::path_save:
    case K::path_load:
    case K::path_clear:
    case K::path_frame:
    case K::path_play: run_path_command(c, line, host); break;
    case K::quit: break;
  }
}

}  // namespace

std::string ids_path_for(const std::string& png_path) {
  return std::filesystem::path(png_path).replace_extension(".ids").string();
}

bool run_command(const ScriptCommand& command, const std::string& file, ScriptHost& host, std::ostream& out) {
  if (command.kind == ScriptCommand::Kind::quit) return false;
  const InputSource line{file, "line " + std::to_string(command.line)};
  try {
    execute(command, line, host, out);
  } catch (const InputError& e) {
    // A refusal thrown against this line already says so; an image or path file that cannot be
    // written or read names only itself, so add which line asked for it.
    if (e.file() == line.file && e.where() == line.where) throw;
    line.fail(e.what());
  } catch (const std::invalid_argument& e) {  // the window closed during the line (ScriptHost::render_frames)
    line.fail(e.what());
  } catch (const std::filesystem::filesystem_error& e) {
    line.fail(e.what());
  }
  return true;
}

}  // namespace nano::viewer
