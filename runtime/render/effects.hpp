#pragma once
// Scene effects of the renderer (paper §5.3 "Visibility Management", §5.4 "Animation"): clipping,
// proxy animation, protein jitter, ambient occlusion and hard shadows. Each is off unless the scene
// (section "effects" of the package) or the user turns it on, and each is compiled into the frame
// only when on (specialization constants of shaders/render/render.comp), so an effect that is off
// costs nothing.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "common/effect_table.hpp"
#include "common/error.hpp"
#include "format/package.hpp"

namespace nano::render {

// Points p with n·p + d ≥ 0 for every plane, and inside the box when there is one, stay visible.
// An atom is kept or removed whole, by its centre; never cut in half.
struct Clipping {
  std::vector<glm::dvec4> planes;  // (n, d), world Å; n need not be unit (it is normalised on use)
  std::optional<std::pair<glm::dvec3, glm::dvec3>> box;  // world min, max
  bool any() const { return !planes.empty() || box.has_value(); }
};
inline constexpr std::size_t kMaxClipPlanes = 8;  // user planes; the box adds 6 half-spaces

// The effects of common/effect_table.hpp, switched on or off, with their parameters, plus clipping's
// planes and box and the moment. The parameters are held in the package's own record, copied from
// the mapped section when opened (an effect the package leaves off starts at the table's fallbacks),
// edited at their slots by the options, the panel and the script, and handed to the shader in that
// same layout (effect_record).
struct EffectSettings {
  std::array<bool, kEffectCount> on{};
  gpu::SceneEffects record = fallback_effect_record();  // its clipping and proxy-motion members are not read
  Clipping clipping;
  double time = 0;                 // seconds: proxy animation and jitter are evaluated at this time
  std::uint32_t sample_index = 0;  // seeds the AO directions; progressive refinement varies it

  bool& flag(EffectId id) { return on[static_cast<std::size_t>(id)]; }
  bool flag(EffectId id) const { return on[static_cast<std::size_t>(id)]; }
  float& number(EffectId id, std::string_view key) { return number_slot(record, effect_parameter(id, key)); }
  float number(EffectId id, std::string_view key) const { return number_slot(record, effect_parameter(id, key)); }

  // The parameters the renderer reads by meaning.
  std::uint32_t ao_rays() const { return std::uint32_t(number(EffectId::ambient_occlusion, "rays")); }
  float ao_radius() const { return number(EffectId::ambient_occlusion, "radius"); }
  double jitter_degrees() const { return number(EffectId::jitter, "amplitude_degrees"); }
  double jitter_hz() const { return number(EffectId::jitter, "frequency_hz"); }
  glm::vec3 light_direction() const { return direction_slot(record, effect_parameter(EffectId::shadows, "light_direction")); }
};

// The effects the package's scene asks for (all off when it has no "effects" section).
EffectSettings package_effects(const format::Package& package);

// The switch of effect `name` (as --effect and the viewer script spell it, common/effect_table.hpp);
// for another name, throws an InputError against `source` (where the name came from) naming the choices.
bool& effect_flag(EffectSettings& effects, std::string_view name, const InputSource& source);
inline void set_effect(EffectSettings& effects, std::string_view name, bool on, const InputSource& source) {
  effect_flag(effects, name, source) = on;
}
// Turns on the effects of preset `name` (common/effect_table.hpp) with its values; for another name,
// throws an InputError against `source` naming the choices.
void apply_preset(EffectSettings& effects, std::string_view name, const InputSource& source);
void apply_preset(EffectSettings& effects, const EffectPreset& preset);
// What the shader reads (RenderFrame::effect_record): the settings' record with the parameters of the
// effects that are on, every other member zero, as in the package.
gpu::SceneEffects effect_record(const EffectSettings& effects);

// Sets `parameter` in `record` from an option's text ("16", "0.2,0.5,1"; unit vectors normalised);
// throws an InputError against `source` saying what the parameter accepts.
void parse_parameter(gpu::SceneEffects& record, const EffectParameter& parameter, std::string_view text, const InputSource& source);
// --help's line for a parameter option.
std::string parameter_help(const EffectDeclaration& effect, const EffectParameter& parameter);

// "nx,ny,nz,d" → plane; "x0,y0,z0,x1,y1,z1" → box. Throw an InputError against `source` saying what
// is wrong.
glm::dvec4 parse_clip_plane(std::string_view text, const InputSource& source);
// (time, amplitude in radians, frequency) as the frame hands them to the shader: the oracle jitters
// with these very floats.
glm::vec3 jitter_frame_parameters(const EffectSettings& effects);

// The half-spaces (unit n, d) a point must satisfy to stay: the planes, then the box's six faces.
std::vector<glm::dvec4> clip_half_spaces(const Clipping& clipping);
std::pair<glm::dvec3, glm::dvec3> parse_clip_box(std::string_view text, const InputSource& source);

}  // namespace nano::render
