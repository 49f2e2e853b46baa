#include "common/effect_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

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

std::size_t parameter_index(EffectId id, std::string_view key) {
  const auto parameters = effect_declaration(id).parameters;
  for (std::size_t i = 0; i < parameters.size(); ++i)
    if (parameters[i].key == key) return i;
  throw std::logic_error("effect " + std::string(effect_declaration(id).name) + " has no parameter " + std::string(key));
}

std::string parameter_option(const EffectDeclaration& effect, const EffectParameter& parameter) {
  if (effect.cli_prefix.empty()) return {};
  std::string key(parameter.key);
  std::replace(key.begin(), key.end(), '_', '-');
  return "--" + std::string(effect.cli_prefix) + "-" + key;
}

EffectValues fallback_effect_values() {
  EffectValues values{};
  for (const EffectDeclaration& e : kEffects)
    for (std::size_t p = 0; p < e.parameters.size(); ++p) values[static_cast<std::size_t>(e.id)][p] = e.parameters[p].fallback;
  return values;
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

void store_parameters(gpu::SceneEffects& record, EffectId id, const ParameterValues& values) {
  auto* bytes = reinterpret_cast<unsigned char*>(&record);
  const auto parameters = effect_declaration(id).parameters;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    const EffectParameter& p = parameters[i];
    switch (p.kind) {
      case ParameterKind::number:
      case ParameterKind::whole_number: {
        const float x = float(values[i].x);
        std::memcpy(bytes + p.record_offset, &x, sizeof x);
        break;
      }
      case ParameterKind::unit_vector: {
        const glm::vec3 v(values[i]);
        std::memcpy(bytes + p.record_offset, &v, sizeof v);
        break;
      }
      case ParameterKind::colour: {
        const std::uint32_t word = pack_colour(values[i]);
        std::memcpy(bytes + p.record_offset, &word, sizeof word);
        break;
      }
    }
  }
}

ParameterValues load_parameters(const gpu::SceneEffects& record, EffectId id) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(&record);
  const auto parameters = effect_declaration(id).parameters;
  ParameterValues values{};
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    const EffectParameter& p = parameters[i];
    switch (p.kind) {
      case ParameterKind::number:
      case ParameterKind::whole_number: {
        float x;
        std::memcpy(&x, bytes + p.record_offset, sizeof x);
        values[i] = glm::dvec3(x, 0.0, 0.0);
        break;
      }
      case ParameterKind::unit_vector: {
        glm::vec3 v;
        std::memcpy(&v, bytes + p.record_offset, sizeof v);
        values[i] = glm::dvec3(v);
        break;
      }
      case ParameterKind::colour: {
        std::uint32_t word;
        std::memcpy(&word, bytes + p.record_offset, sizeof word);
        values[i] = unpack_colour(word);
        break;
      }
    }
  }
  return values;
}

}  // namespace nano
