#include "common/effect_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <new>
#include <stdexcept>
#include <type_traits>

#include <glm/geometric.hpp>

#include "shared/bindings.h"

namespace nano {
namespace {

constexpr double kNoLimit = std::numeric_limits<double>::infinity();

// Slots by member name: the record's layout is gpu::SceneEffects's, nowhere typed twice.
#define NANO_SLOT(member) std::uint32_t(offsetof(gpu::SceneEffects, member))
#define NANO_SLOT_AFTER(member, words) std::uint32_t(offsetof(gpu::SceneEffects, member) + 4 * (words))

constexpr EffectParameter kJitter[] = {
    {"amplitude_degrees", "°", ParameterKind::number, 0, 180, false, true, {5, 0, 0}, NANO_SLOT(jitter), PanelWidget::slider, 0, 45},
    {"frequency_hz", "Hz", ParameterKind::number, 0, kNoLimit, true, true, {1, 0, 0}, NANO_SLOT_AFTER(jitter, 1), PanelWidget::log_slider, 0.01, 100},
};
// radius_pixels keeps the occlusion visible from afar: the rays reach at least that many pixels'
// footprint at the hit, so a cell seen whole darkens its folds as a protein seen close does its clefts.
constexpr EffectParameter kAmbientOcclusion[] = {
    {"rays", "", ParameterKind::whole_number, 1, 1024, false, true, {8, 0, 0}, NANO_SLOT(ambient_occlusion), PanelWidget::slider, 1, 64},
    {"radius", "Å", ParameterKind::number, 0, kNoLimit, true, true, {40, 0, 0}, NANO_SLOT_AFTER(ambient_occlusion, 1), PanelWidget::log_slider, 1, 2000},
    {"radius_pixels", "px", ParameterKind::number, 0, 256, false, false, {0, 0, 0}, NANO_SLOT(ao_radius_pixels), PanelWidget::slider, 0, 64},
};
constexpr EffectParameter kShadows[] = {
    {"light_direction", "", ParameterKind::unit_vector, 0, 0, false, true, {0.3, 0.5, 0.8}, NANO_SLOT(shadow_light), PanelWidget::direction, -1, 1},
};
// Goodsell's and Mol*'s illustrative contours: silhouettes where the molecule copy changes, creases
// where one copy folds over itself by more than crease_depth; both fade out as the copy shrinks below
// fade_pixels on screen (0: never), so a membrane seen whole is not drawn as a mesh of lines.
constexpr EffectParameter kOutlines[] = {
    {"width_pixels", "px", ParameterKind::whole_number, 1, 8, false, false, {1, 0, 0}, NANO_SLOT(outline_width_pixels), PanelWidget::slider, 1, 8},
    {"crease_depth", "Å", ParameterKind::number, 0, kNoLimit, true, false, {5, 0, 0}, NANO_SLOT(outline_crease_depth), PanelWidget::log_slider, 0.5, 100},
    {"colour", "", ParameterKind::colour, 0, 1, false, false, {0, 0, 0}, NANO_SLOT(outline_colour), PanelWidget::colour_picker, 0, 1},
    {"fade_pixels", "px", ParameterKind::number, 0, 256, false, false, {12, 0, 0}, NANO_SLOT(outline_fade_pixels), PanelWidget::slider, 0, 32},
};
// Depth cueing measured in the frame's own depth range (nearest to farthest hit of an 8 × 8 grid of its
// pixels), so it reads the same from a whole cell down to one protein: colour fades towards the
// background from start over span of that range, at most by strength.
constexpr EffectParameter kFog[] = {
    {"start", "× depth range", ParameterKind::number, 0, 10, false, false, {0, 0, 0}, NANO_SLOT(fog_range), PanelWidget::slider, 0, 1},
    {"span", "× depth range", ParameterKind::number, 0, 10, true, false, {1, 0, 0}, NANO_SLOT_AFTER(fog_range, 1), PanelWidget::log_slider, 0.05, 10},
    {"strength", "", ParameterKind::number, 0, 1, false, false, {0.6, 0, 0}, NANO_SLOT(fog_strength), PanelWidget::slider, 0, 1},
};
#undef NANO_SLOT
#undef NANO_SLOT_AFTER

constexpr EffectDeclaration kEffects[] = {
    {EffectId::clipping, "clipping", "clipping", "", "keep what lies inside up to 8 planes and a box (an atom whole, by its centre)",
     1u, gpu::NANO_SPEC_CLIPPING, {}, "planes, box", "clips atoms by centre with the same half-spaces", false},
    {EffectId::animation, "animation", "animation", "", "compartment instances move: steady spin and drift, or keyframes",
     2u, -1, {}, "enabled, proxy_motion", "moves the instances to the same pose", false},
    {EffectId::jitter, "jitter", "animation.jitter", "jitter", "each protein copy wobbles about its own origin",
     4u, gpu::NANO_SPEC_JITTER, kJitter, "", "jitters each copy with shared/effects.h", false},
    {EffectId::ambient_occlusion, "ao", "ambient_occlusion", "ao", "short rays per pixel darken what is enclosed",
     8u, gpu::NANO_SPEC_AMBIENT_OCCLUSION, kAmbientOcclusion, "", "none: colour only (render.effects.shading checks it)", false},
    {EffectId::shadows, "shadows", "shadows", "shadows", "one ray a pixel towards the light",
     16u, gpu::NANO_SPEC_SHADOWS, kShadows, "", "none: colour only (render.effects.shading checks it)", false},
    {EffectId::outlines, "outlines", "outlines", "outlines", "contours where the molecule or the depth changes between pixels, fading with the copy's size on screen",
     32u, gpu::NANO_SPEC_OUTLINES, kOutlines, "", "none: colour only (render.effects.outlines checks it against the ids image)", true},
    {EffectId::fog, "fog", "fog", "fog", "depth cueing: the farther within the frame's depth range, the paler",
     64u, gpu::NANO_SPEC_FOG, kFog, "", "none: colour only (render.effects.fog checks it against the depths)", true},
};
// Goodsell's plates: contours that fade with a copy's size on screen, depth cueing over the frame's depths,
// occlusion that reaches 8 pixels whatever the distance (chosen on the virion, the red blood cell and
// blood at four distances each: docs/effects.md).
constexpr PresetEffect kIllustrative[] = {
    {EffectId::outlines, {glm::dvec3(1, 0, 0), glm::dvec3(5, 0, 0), glm::dvec3(0, 0, 0), glm::dvec3(12, 0, 0)}},
    {EffectId::fog, {glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0.5, 0, 0), glm::dvec3(0)}},
    {EffectId::ambient_occlusion, {glm::dvec3(8, 0, 0), glm::dvec3(40, 0, 0), glm::dvec3(8, 0, 0), glm::dvec3(0)}},
};
constexpr EffectPreset kPresets[] = {
    {"illustrative", "outlines that fade with a copy's size, fog over the frame's depths, occlusion at every scale", kIllustrative},
};

static_assert(std::size(kEffects) == kEffectCount, "one row per EffectId");

constexpr bool rows_in_id_order() {
  for (std::size_t i = 0; i < std::size(kEffects); ++i)
    if (static_cast<std::size_t>(kEffects[i].id) != i) return false;
  return true;
}
static_assert(rows_in_id_order(), "row i declares EffectId i");

constexpr bool parameters_fit() {
  for (const EffectDeclaration& e : kEffects)
    if (e.parameters.size() > kMaxEffectParameters) return false;
  return true;
}
static_assert(parameters_fit(), "raise kMaxEffectParameters");

constexpr std::uint32_t slot_bytes(ParameterKind kind) { return kind == ParameterKind::unit_vector ? 12u : 4u; }
// Slots inside the record, word-aligned and disjoint: two effects never write the same bytes.
constexpr bool slots_disjoint() {
  for (const EffectDeclaration& a : kEffects)
    for (const EffectParameter& p : a.parameters) {
      if (p.record_offset % 4 != 0 || p.record_offset + slot_bytes(p.kind) > sizeof(gpu::SceneEffects)) return false;
      for (const EffectDeclaration& b : kEffects)
        for (const EffectParameter& q : b.parameters)
          if (&p != &q && p.record_offset < q.record_offset + slot_bytes(q.kind) && q.record_offset < p.record_offset + slot_bytes(p.kind))
            return false;
    }
  return true;
}
static_assert(slots_disjoint(), "parameter slots overlap or leave gpu::SceneEffects");

}  // namespace

std::span<const EffectDeclaration> effect_table() { return kEffects; }

const EffectDeclaration& effect_declaration(EffectId id) { return kEffects[static_cast<std::size_t>(id)]; }

const EffectDeclaration* find_effect(std::string_view name) {
  for (const EffectDeclaration& e : kEffects)
    if (e.name == name) return &e;
  return nullptr;
}

std::span<const EffectPreset> effect_presets() { return kPresets; }

const EffectPreset* find_preset(std::string_view name) {
  for (const EffectPreset& p : kPresets)
    if (p.name == name) return &p;
  return nullptr;
}

std::string preset_names() {
  std::string names;
  for (const EffectPreset& p : kPresets) names += (names.empty() ? "" : ", ") + std::string(p.name);
  return names;
}

std::string effect_names() {
  std::string names;
  for (const EffectDeclaration& e : kEffects) names += (names.empty() ? "" : ", ") + std::string(e.name);
  return names;
}

const EffectParameter& effect_parameter(EffectId id, std::string_view key) {
  for (const EffectParameter& p : effect_declaration(id).parameters)
    if (p.key == key) return p;
  throw std::logic_error("effect " + std::string(effect_declaration(id).name) + " has no parameter " + std::string(key));
}

std::string parameter_option(const EffectDeclaration& effect, const EffectParameter& parameter) {
  if (effect.cli_prefix.empty()) return {};
  std::string key(parameter.key);
  std::replace(key.begin(), key.end(), '_', '-');
  return "--" + std::string(effect.cli_prefix) + "-" + key;
}

std::string shown_number(double x) {
  std::string s = std::to_string(x);
  s.erase(s.find_last_not_of('0') + 1);
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

std::string parameter_range(const EffectParameter& p) {
  const std::string unit = p.unit.empty() ? "" : " " + std::string(p.unit);
  if (std::isinf(p.max)) return std::string(p.min_exclusive ? "> " : ">= ") + shown_number(p.min) + unit;
  return "in " + std::string(p.min_exclusive ? "(" : "[") + shown_number(p.min) + ", " + shown_number(p.max) + "]" + unit;
}

std::string parameter_problem(const EffectParameter& p, const glm::dvec3& v) {
  switch (p.kind) {
    case ParameterKind::number:
    case ParameterKind::whole_number: {
      const double x = v.x;
      if (!std::isfinite(x)) return "must be a finite number";
      if (p.kind == ParameterKind::whole_number && x != std::floor(x)) return "must be a whole number";
      const bool low = p.min_exclusive ? !(x > p.min) : !(x >= p.min);
      if (low || !(x <= p.max)) return "must be " + parameter_range(p);
      return {};
    }
    case ParameterKind::unit_vector:
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) return "must be three finite numbers";
      if (v == glm::dvec3(0.0)) return "must be a non-zero direction";
      return {};
    case ParameterKind::colour:
      for (int i = 0; i < 3; ++i)
        if (!(v[i] >= 0.0 && v[i] <= 1.0)) return "must be three numbers in [0, 1] (red, green, blue as the image shows them)";
      return {};
  }
  return "unknown parameter kind";
}

std::uint32_t pack_colour(const glm::dvec3& rgb) {
  std::uint32_t word = 255u << 24;
  for (int i = 0; i < 3; ++i) word |= std::uint32_t(std::lround(std::clamp(rgb[i], 0.0, 1.0) * 255.0)) << (8 * i);
  return word;
}

glm::dvec3 unpack_colour(std::uint32_t rgba) {
  return {double(rgba & 0xFFu) / 255.0, double((rgba >> 8) & 0xFFu) / 255.0, double((rgba >> 16) & 0xFFu) / 255.0};
}

namespace {

// The member at the parameter's offset, which the table's slots_disjoint() keeps inside the record;
// `fits`: the parameter is of a kind the record holds as T.
template <class T, class Record>
auto& slot(Record& record, const EffectParameter& p, bool fits) {
  if (!fits) throw std::logic_error("parameter " + std::string(p.key) + " is not held as this type");
  using Byte = std::conditional_t<std::is_const_v<Record>, const unsigned char, unsigned char>;
  using Member = std::conditional_t<std::is_const_v<Record>, const T, T>;
  return *std::launder(reinterpret_cast<Member*>(reinterpret_cast<Byte*>(&record) + p.record_offset));
}

bool is_number(const EffectParameter& p) { return p.kind == ParameterKind::number || p.kind == ParameterKind::whole_number; }

}  // namespace

float& number_slot(gpu::SceneEffects& r, const EffectParameter& p) { return slot<float>(r, p, is_number(p)); }
const float& number_slot(const gpu::SceneEffects& r, const EffectParameter& p) { return slot<float>(r, p, is_number(p)); }
glm::vec3& direction_slot(gpu::SceneEffects& r, const EffectParameter& p) {
  return slot<glm::vec3>(r, p, p.kind == ParameterKind::unit_vector);
}
const glm::vec3& direction_slot(const gpu::SceneEffects& r, const EffectParameter& p) {
  return slot<glm::vec3>(r, p, p.kind == ParameterKind::unit_vector);
}
std::uint32_t& colour_slot(gpu::SceneEffects& r, const EffectParameter& p) {
  return slot<std::uint32_t>(r, p, p.kind == ParameterKind::colour);
}
const std::uint32_t& colour_slot(const gpu::SceneEffects& r, const EffectParameter& p) {
  return slot<std::uint32_t>(r, p, p.kind == ParameterKind::colour);
}

void set_parameter(gpu::SceneEffects& record, const EffectParameter& p, const glm::dvec3& value) {
  switch (p.kind) {
    case ParameterKind::number:
    case ParameterKind::whole_number: number_slot(record, p) = float(value.x); break;
    case ParameterKind::unit_vector: direction_slot(record, p) = glm::vec3(value); break;
    case ParameterKind::colour: colour_slot(record, p) = pack_colour(value); break;
  }
}

gpu::SceneEffects fallback_effect_record() {
  gpu::SceneEffects record{};
  for (const EffectDeclaration& e : kEffects)
    for (const EffectParameter& p : e.parameters) set_parameter(record, p, p.fallback);
  return record;
}

void set_preset_parameters(gpu::SceneEffects& record, const PresetEffect& effect) {
  const auto parameters = effect_declaration(effect.id).parameters;
  for (std::size_t i = 0; i < parameters.size(); ++i) set_parameter(record, parameters[i], effect.values[i]);
}

void copy_parameters(gpu::SceneEffects& to, const gpu::SceneEffects& from, EffectId id) {
  for (const EffectParameter& p : effect_declaration(id).parameters)
    std::memcpy(reinterpret_cast<unsigned char*>(&to) + p.record_offset, reinterpret_cast<const unsigned char*>(&from) + p.record_offset,
                slot_bytes(p.kind));
}

}  // namespace nano
