#include "runtime/session/oracle_view.hpp"

#include "runtime/placement/visibility.hpp"
#include "runtime/render/animation.hpp"

namespace nano::session {

OracleEffects oracle_effects(const format::Package& package, const render::EffectSettings& effects) {
  OracleEffects o;
  if (effects.flag(EffectId::animation)) o.scene.instance_transforms = render::animated_instance_transforms(package, effects.time);
  o.scene.jitter = effects.flag(EffectId::jitter) && effects.jitter_degrees() > 0;
  o.scene.jitter_parameters = render::jitter_frame_parameters(effects);
  if (effects.flag(EffectId::clipping)) o.clip = render::clip_half_spaces(effects.clipping);
  o.scene.clip = o.clip;
  return o;
}

void hide_from_oracle(const format::Package& package, const render::RenderSettings& settings, oracle::ExplicitSceneOptions& scene) {
  scene.medium = settings.show_medium;
  scene.visibility = placement::resolve_hidden(package, settings.hidden);
}

}  // namespace nano::session
