#pragma once
// The session's settings as the CPU oracle needs them (verify, pick, bench's accuracy matrix): kept
// apart from session.hpp so that the viewer, which never checks a frame, does not link the oracle.
#include <vector>

#include <glm/vec4.hpp>

#include "format/package.hpp"
#include "runtime/oracle/explicit_scene.hpp"
#include "runtime/render/effects.hpp"
#include "runtime/render/renderer.hpp"

namespace nano::session {

// What the effects change for the CPU oracle, as the renderer applies them: moved instances and
// jittered copies (the scene) and clipped atoms (the render options). AO and shadows change colours
// only, which the oracle does not produce.
struct OracleEffects {
  oracle::ExplicitSceneOptions scene;
  std::vector<glm::dvec4> clip;
};
OracleEffects oracle_effects(const format::Package& package, const render::EffectSettings& effects);
// What the settings hide (--hide: the medium, compartments, molecule types), for the oracle as the
// renderer hides it. Throws InputError naming --hide for a name the package does not have.
void hide_from_oracle(const format::Package& package, const render::RenderSettings& settings, oracle::ExplicitSceneOptions& scene);

}  // namespace nano::session
