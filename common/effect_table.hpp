#pragma once
// Every scene effect, declared once. The scene parser, the baker, the validator, the renderer's
// specialization constants, the command-line options, the viewer's panel and `bench --effects` all
// walk this table, so an effect is added by one row here, its shader code and its record slots.
//
// An effect's plain parameters (numbers, directions, colours) need nothing else: they are parsed
// from scene.json at `scene_key`, stored as floats (or a packed colour) at `record_offset` of the
// package's effects record (gpu::SceneEffects), range-checked by the validator, given an option
// `--<cli_prefix>-<key>` and a panel widget, and handed to the shader in RenderFrame::effect_record.
// Clipping's planes and box and animation's proxy motion are structured (lists, keyframes): the
// table names them in `structured`, and their own code parses, bakes and checks them.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "shared/package_records.h"

namespace nano {

enum class EffectId : std::uint8_t { clipping, animation, jitter, ambient_occlusion, shadows, outlines, fog };
inline constexpr std::size_t kEffectCount = 7;
inline constexpr std::size_t kMaxEffectParameters = 4;

enum class ParameterKind : std::uint8_t {
  number,        // one float
  whole_number,  // one float holding an integer
  unit_vector,   // three floats, normalised when parsed
  colour,        // RGB in [0, 1] as the image shows it (sRGB), stored as one RGBA8 word (alpha 255)
};
enum class PanelWidget : std::uint8_t { slider, log_slider, direction, colour_picker };

struct EffectParameter {
  std::string_view key;   // in the effect's scene object; the option is --<cli_prefix>-<key, '_' → '-'>
  std::string_view unit;  // "Å", "px", "°", "Hz", "× depth range" or "" (shown by --help and the panel)
  ParameterKind kind;
  double min, max;        // numbers: the accepted range; min is excluded when min_exclusive
  bool min_exclusive;
  bool required;          // the scene must give it when it gives the effect; else `fallback`
  glm::dvec3 fallback;    // the value when the scene does not set it (numbers in x)
  std::uint32_t record_offset;  // byte offset of its first word in gpu::SceneEffects
  PanelWidget widget;
  double panel_min, panel_max;
};

struct EffectDeclaration {
  EffectId id;
  std::string_view name;        // --effect NAME, the viewer's switch and script, bench's row
  std::string_view scene_key;   // where scene.json sets it, under "effects" ("animation.jitter": nested)
  std::string_view cli_prefix;  // options --<prefix>-<parameter>; empty: no parameter options
  std::string_view summary;     // one line for --help and docs
  std::uint32_t package_flag;   // its bit of gpu::SceneSettings::effect_flags (file format: never reuse)
  int spec_constant;            // render.comp's constant_id; -1: no shader code (animation moves instances on the host)
  std::span<const EffectParameter> parameters;
  std::string_view structured;  // parts read by the effect's own code; empty for none
  std::string_view oracle;      // how the CPU oracle (verify) reproduces it
  bool image_pass;              // needs the finished hits image: render.comp's second dispatch
};

std::span<const EffectDeclaration> effect_table();
const EffectDeclaration& effect_declaration(EffectId id);
inline std::uint32_t package_flag(EffectId id) { return effect_declaration(id).package_flag; }
// By name (as --effect spells it); nullptr for another name.
const EffectDeclaration* find_effect(std::string_view name);
// "clipping, animation, jitter, ao, shadows, outlines, fog": the choices an error message lists.
std::string effect_names();
// The parameter `key` of effect `id`; throws std::logic_error for a key it does not have.
const EffectParameter& effect_parameter(EffectId id, std::string_view key);
// "--ao-rays"; empty when the effect has no parameter options.
std::string parameter_option(const EffectDeclaration& effect, const EffectParameter& parameter);

// A parameter's slot in an effects record, typed as the record holds it: a number (or whole number)
// is one float, a unit vector a vec3, a colour one RGBA8 word. The package's section, the settings
// that the options, the panel and the script edit, and the frame's copy the shader reads are one
// gpu::SceneEffects each, so a parameter is read and edited at its member, never converted on the
// way. Each throws std::logic_error for a parameter of another kind.
float& number_slot(gpu::SceneEffects& record, const EffectParameter& parameter);
const float& number_slot(const gpu::SceneEffects& record, const EffectParameter& parameter);
glm::vec3& direction_slot(gpu::SceneEffects& record, const EffectParameter& parameter);
const glm::vec3& direction_slot(const gpu::SceneEffects& record, const EffectParameter& parameter);
std::uint32_t& colour_slot(gpu::SceneEffects& record, const EffectParameter& parameter);
const std::uint32_t& colour_slot(const gpu::SceneEffects& record, const EffectParameter& parameter);

// Writes a value as scene.json, an option or the table gives it (numbers in x; unit vectors as
// given, every parser normalises in double; colours in [0, 1]) into the parameter's slot.
void set_parameter(gpu::SceneEffects& record, const EffectParameter& parameter, const glm::dvec3& value);
// Every table parameter at its fallback; every other member zero.
gpu::SceneEffects fallback_effect_record();
// Copies effect `id`'s parameter slots from `from` into `to`; the rest of `to` stays as it is.
void copy_parameters(gpu::SceneEffects& to, const gpu::SceneEffects& from, EffectId id);

// A number's range as messages and --help print it: "> 0 Å", "in [1, 8] px".
std::string parameter_range(const EffectParameter& parameter);
// The shortest decimal text of a table value (5, 0.3, 1024).
std::string shown_number(double x);
// Why `value` is not acceptable for `parameter`, or empty when it is (unit vectors: non-zero
// finite; the caller normalises).
std::string parameter_problem(const EffectParameter& parameter, const glm::dvec3& value);
// The RGBA8 word of a colour parameter (R in the low byte, alpha 255) and back.
std::uint32_t pack_colour(const glm::dvec3& rgb);
glm::dvec3 unpack_colour(std::uint32_t rgba);

// A named combination of effects with parameters chosen by looking at every bundled scene from afar
// and close (docs/effects.md): the scene's "effects": {"preset": NAME}, --preset NAME, the viewer's
// panel and its script's `preset NAME`. A preset turns its effects on with its values; what the scene
// or the options set explicitly wins.
struct PresetEffect {
  EffectId id;
  std::array<glm::dvec3, kMaxEffectParameters> values;  // every parameter of the effect, in table order, as scene.json gives it
};
// Writes the preset's values of one effect into `record`'s slots.
void set_preset_parameters(gpu::SceneEffects& record, const PresetEffect& effect);
struct EffectPreset {
  std::string_view name;
  std::string_view summary;
  std::span<const PresetEffect> effects;
};
std::span<const EffectPreset> effect_presets();
const EffectPreset* find_preset(std::string_view name);  // nullptr for another name
std::string preset_names();                               // "illustrative": the choices a message lists

}  // namespace nano

namespace nano::gpu {
// Records compare by their bytes (a scene description with its effects' record compares whole).
inline bool operator==(const SceneEffects& a, const SceneEffects& b) { return std::memcmp(&a, &b, sizeof a) == 0; }
}  // namespace nano::gpu
