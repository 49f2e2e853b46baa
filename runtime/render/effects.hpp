#pragma once
// Scene effects of the renderer (paper §5.3 "Visibility Management", §5.4 "Animation"): clipping,
// proxy animation, protein jitter, ambient occlusion and hard shadows. Each is off unless the scene
// (section "effects" of the package) or the user turns it on, and each is compiled into the frame
// only when on (specialization constants of shaders/render/render.comp), so an effect that is off
// costs nothing.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

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

struct EffectSettings {
  bool clipping_on = false;
  Clipping clipping;

  double time = 0;              // seconds: proxy animation and jitter are evaluated at this time
  bool animation_on = false;    // compartment instances move as the package's animation says
  bool jitter_on = false;       // proteins wobble about their own origin (shared/effects.h)
  double jitter_degrees = 5, jitter_hz = 1;  // what a user gets asking for jitter the scene does not set

  bool ambient_occlusion_on = false;
  std::uint32_t ao_rays = 8;
  float ao_radius = 40;         // Å
  std::uint32_t sample_index = 0;  // seeds the AO directions; progressive refinement varies it

  bool shadows_on = false;
  glm::dvec3 light_direction{0.3, 0.5, 0.8};  // towards the light (world)
};

// The effects the package's scene asks for (all off when it has no "effects" section).
EffectSettings package_effects(const format::Package& package);

// Names of the switchable effects, as the CLI and the viewer script spell them.
inline constexpr std::string_view kEffectNames[] = {"clipping", "animation", "jitter", "ao", "shadows"};
// The switch of effect `name` (one of kEffectNames); throws std::invalid_argument naming the
// choices for another name.
bool& effect_flag(EffectSettings& effects, std::string_view name);
inline void set_effect(EffectSettings& effects, std::string_view name, bool on) { effect_flag(effects, name) = on; }

// "nx,ny,nz,d" → plane; "x0,y0,z0,x1,y1,z1" → box. Throw std::invalid_argument saying what is wrong.
glm::dvec4 parse_clip_plane(std::string_view text);
// (time, amplitude in radians, frequency) as the frame hands them to the shader: the oracle jitters
// with these very floats.
glm::vec3 jitter_frame_parameters(const EffectSettings& effects);

// The half-spaces (unit n, d) a point must satisfy to stay: the planes, then the box's six faces.
std::vector<glm::dvec4> clip_half_spaces(const Clipping& clipping);
std::pair<glm::dvec3, glm::dvec3> parse_clip_box(std::string_view text);

}  // namespace nano::render
