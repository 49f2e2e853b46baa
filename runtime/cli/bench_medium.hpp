#pragma once
// `nanoview bench PKG --medium`: what a scene's medium (its plasma) costs where users look, in one
// run: at the scene camera and at a close-up in the medium facing a cell, each view with the medium
// and without it (the same package and device, `--hide medium`), frames timed alternately, and the
// work per pixel at every level of the traversal for all four, so the table says where the time goes.
#include <string>

#include <nlohmann/json.hpp>

#include "runtime/render/renderer.hpp"
#include "runtime/session/session.hpp"

namespace nano::cli {

struct MediumBenchOptions {
  std::string size = "128x128";
  unsigned rounds = 5;
  std::string scene_camera;  // --camera: keys given replace the package camera's
  std::string close_up;      // --close-up: empty chooses one (see run_medium_bench)
  double close_up_gap = 600; // Å between the close-up's eye and the first atom it faces
  render::RenderSettings settings;
};

// Without --close-up, the close-up looks from the scene camera towards the compartment instance
// nearest its target, from `close_up_gap` Å in front of the first atom that line meets without the
// medium (the cell's membrane), 30° wide. Throws InputError when the package has no medium, or
// when that line meets nothing.
void run_medium_bench(const MediumBenchOptions& o, session::RenderSession& session, nlohmann::ordered_json& out);

}  // namespace nano::cli
