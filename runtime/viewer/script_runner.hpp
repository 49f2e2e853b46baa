#pragma once
// Runs parsed script commands against the viewer through ScriptHost, the little the commands need
// from the window and the renderer — so the runner is tested with a fake host and no display.
#include <cstdint>
#include <ostream>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "runtime/render/renderer.hpp"
#include "runtime/viewer/script.hpp"
#include "runtime/viewer/viewer_state.hpp"

namespace nano::viewer {

class ScriptHost {
public:
  virtual ~ScriptHost() = default;
  virtual ViewerState& state() = 0;
  // Renders and shows `count` full-resolution frames of the current state.
  virtual void render_frames(std::uint32_t count) = 0;
  // The last full-resolution frame, rendered first if the state changed since (never a reduced
  // progressive frame), and the image shown for it (the average of its AO samples, or its rgba).
  virtual const render::Frame& current_frame() = 0;
  virtual std::span<const std::uint32_t> current_image() = 0;
  // Render size (and window size) from now on.
  virtual void resize(std::uint32_t width, std::uint32_t height) = 0;
  virtual nlohmann::json describe(const gpu::PixelHit& hit) = 0;
};

// Executes one command; false for `quit`. Every failure (a camera that becomes degenerate, a ninth
// clip plane, a pick outside the image, a file that cannot be written or read, a keyframe out of
// order, a path frame past the end) is an InputError naming `file` and the command's line.
bool run_command(const ScriptCommand& command, const std::string& file, ScriptHost& host, std::ostream& out);

// The .ids file written beside a screenshot: PATH with extension .ids.
std::string ids_path_for(const std::string& png_path);

}  // namespace nano::viewer
