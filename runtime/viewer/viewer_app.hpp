#pragma once
// `nanoview view`: the window, the session on a presentation-capable device, the renderer, the
// main loop with progressive refinement, and the script driver.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "runtime/session/session.hpp"

namespace nano::viewer {

struct ViewerOptions {
  std::string package;
  std::string script;                                       // empty: interactive
  std::optional<std::pair<std::uint32_t, std::uint32_t>> size;  // window; with a script also the render size
  std::string camera;                                       // start camera (keys left out: the package's)
  std::string path;                                         // camera path (JSON) to start with; empty: none
  bool stay = false;                                        // after the script, stay interactive
  std::uint32_t ao_samples = 16;
  session::VariantOptions variant;
  session::EffectOptions effects;
};

// Returns the process exit status; throws InputError / std::runtime_error for failures.
int run_viewer(const ViewerOptions& options);

}  // namespace nano::viewer
