#include "runtime/render/effects.hpp"

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace nano::render {
namespace {

// Exactly `n` comma-separated finite numbers.
std::vector<double> numbers(std::string_view text, std::size_t n, const char* what, const InputSource& source) {
  std::vector<double> v;
  std::string s(text);
  const char* p = s.c_str();
  while (true) {
    char* end = nullptr;
    const double x = std::strtod(p, &end);
    if (end == p || !std::isfinite(x))
      source.fail(std::string(what) + ": expected " + std::to_string(n) + " comma-separated numbers, got '" + s + "'");
    v.push_back(x);
    while (*end == ' ') ++end;
    if (*end == '\0') break;
    if (*end != ',') source.fail(std::string(what) + ": unexpected '" + std::string(1, *end) + "' in '" + s + "'");
    p = end + 1;
  }
  if (v.size() != n)
    source.fail(std::string(what) + ": expected " + std::to_string(n) + " numbers, got " + std::to_string(v.size()) + " in '" + s + "'");
  return v;
}

}  // namespace

EffectSettings package_effects(const format::Package& package) {
  using format::SectionKind;
  EffectSettings e;
  if (package.record_count(SectionKind::effects) != 1 || package.record_count(SectionKind::scene) != 1) return e;
  const std::uint32_t flags = package.records<SectionKind::scene>()[0].effect_flags;
  const gpu::SceneEffects& r = package.records<SectionKind::effects>()[0];
  e.record = r;  // validated when the package was opened
  // The package holds zeros for an effect it leaves off; switched on later, it starts at the table's fallbacks.
  const gpu::SceneEffects fallbacks = fallback_effect_record();
  for (const EffectDeclaration& effect : effect_table()) {
    e.flag(effect.id) = (flags & effect.package_flag) != 0;
    if (!e.flag(effect.id)) copy_parameters(e.record, fallbacks, effect.id);
  }
  if (e.flag(EffectId::clipping)) {
    for (std::uint32_t k = 0; k < r.clip_plane_count && k < gpu::NANO_MAX_CLIP_PLANES; ++k)
      e.clipping.planes.push_back(glm::dvec4(r.clip_planes[k]));
    if (r.clip_box_min.w == 1.f) e.clipping.box = {glm::dvec3(r.clip_box_min), glm::dvec3(r.clip_box_max)};
  }
  return e;
}

bool& effect_flag(EffectSettings& effects, std::string_view name, const InputSource& source) {
  if (const EffectDeclaration* effect = find_effect(name)) return effects.flag(effect->id);
  source.fail("unknown effect '" + std::string(name) + "' (" + effect_names() + ")");
}

void apply_preset(EffectSettings& effects, std::string_view name, const InputSource& source) {
  const EffectPreset* preset = find_preset(name);
  if (!preset) source.fail("unknown preset '" + std::string(name) + "' (" + preset_names() + ")");
  apply_preset(effects, *preset);
}

void apply_preset(EffectSettings& effects, const EffectPreset& preset) {
  for (const PresetEffect& effect : preset.effects) {
    effects.flag(effect.id) = true;
    set_preset_parameters(effects.record, effect);
  }
}

gpu::SceneEffects effect_record(const EffectSettings& effects) {
  gpu::SceneEffects record{};
  for (const EffectDeclaration& effect : effect_table())
    if (effects.flag(effect.id)) copy_parameters(record, effects.record, effect.id);
  return record;
}

void parse_parameter(gpu::SceneEffects& record, const EffectParameter& parameter, std::string_view text, const InputSource& source) {
  const bool vector = parameter.kind == ParameterKind::unit_vector || parameter.kind == ParameterKind::colour;
  const std::vector<double> v = numbers(text, vector ? 3 : 1, vector ? "x,y,z" : "a number", source);
  glm::dvec3 value = vector ? glm::dvec3(v[0], v[1], v[2]) : glm::dvec3(v[0], 0.0, 0.0);
  if (const std::string problem = parameter_problem(parameter, value); !problem.empty())
    source.fail(std::string(parameter.key) + " " + problem + ", got '" + std::string(text) + "'");
  if (parameter.kind == ParameterKind::unit_vector) value = glm::normalize(value);
  set_parameter(record, parameter, value);
}

std::string parameter_help(const EffectDeclaration& effect, const EffectParameter& p) {
  const glm::dvec3& f = p.fallback;
  std::string what = std::string(effect.name) + " " + std::string(p.key) + " (";
  switch (p.kind) {
    case ParameterKind::number: what += "a number " + parameter_range(p); break;
    case ParameterKind::whole_number: what += "a whole number " + parameter_range(p); break;
    case ParameterKind::unit_vector: what += "x,y,z, any length"; break;
    case ParameterKind::colour: what += "r,g,b in [0, 1], as the image shows it"; break;
  }
  what += "; default: the scene's, or " + shown_number(f.x);
  if (p.kind == ParameterKind::unit_vector || p.kind == ParameterKind::colour) what += "," + shown_number(f.y) + "," + shown_number(f.z);
  return what + "); sets the value, --effect " + std::string(effect.name) + " turns it on";
}

glm::dvec4 parse_clip_plane(std::string_view text, const InputSource& source) {
  const std::vector<double> v = numbers(text, 4, "clip plane nx,ny,nz,d", source);
  const glm::dvec3 n(v[0], v[1], v[2]);
  const double length = glm::length(n);
  if (!(length > 0)) source.fail("clip plane nx,ny,nz,d: the normal must be non-zero, got '" + std::string(text) + "'");
  return glm::dvec4(n / length, v[3] / length);
}

std::pair<glm::dvec3, glm::dvec3> parse_clip_box(std::string_view text, const InputSource& source) {
  const std::vector<double> v = numbers(text, 6, "clip box x0,y0,z0,x1,y1,z1", source);
  const glm::dvec3 lo(v[0], v[1], v[2]), hi(v[3], v[4], v[5]);
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
    source.fail("clip box x0,y0,z0,x1,y1,z1: expected x0 < x1, y0 < y1 and z0 < z1, got '" + std::string(text) + "'");
  return {lo, hi};
}

glm::vec3 jitter_frame_parameters(const EffectSettings& e) {
  return {float(e.time), float(glm::radians(e.jitter_degrees())), float(e.jitter_hz())};
}

std::vector<glm::dvec4> clip_half_spaces(const Clipping& clipping) {
  std::vector<glm::dvec4> out;
  for (const glm::dvec4& p : clipping.planes) {
    const double length = glm::length(glm::dvec3(p));
    if (!(length > 0) || !std::isfinite(length)) throw std::invalid_argument("clip plane with a zero or non-finite normal");
    out.push_back(p / length);
  }
  if (clipping.box) {
    const auto& [lo, hi] = *clipping.box;
    for (int a = 0; a < 3; ++a) {
      glm::dvec4 low(0.0), high(0.0);
      low[a] = 1, low.w = -lo[a];    // x − lo ≥ 0
      high[a] = -1, high.w = hi[a];  // hi − x ≥ 0
      out.push_back(low);
      out.push_back(high);
    }
  }
  return out;
}

}  // namespace nano::render
