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
std::vector<double> numbers(std::string_view text, std::size_t n, const char* what) {
  std::vector<double> v;
  std::string s(text);
  const char* p = s.c_str();
  while (true) {
    char* end = nullptr;
    const double x = std::strtod(p, &end);
    if (end == p || !std::isfinite(x))
      throw std::invalid_argument(std::string(what) + ": expected " + std::to_string(n) + " comma-separated numbers, got '" + s + "'");
    v.push_back(x);
    while (*end == ' ') ++end;
    if (*end == '\0') break;
    if (*end != ',') throw std::invalid_argument(std::string(what) + ": unexpected '" + std::string(1, *end) + "' in '" + s + "'");
    p = end + 1;
  }
  if (v.size() != n)
    throw std::invalid_argument(std::string(what) + ": expected " + std::to_string(n) + " numbers, got " + std::to_string(v.size()) +
                                " in '" + s + "'");
  return v;
}

}  // namespace

EffectSettings package_effects(const format::Package& package) {
  using format::SectionKind;
  EffectSettings e;
  if (package.record_count(SectionKind::effects) != 1 || package.record_count(SectionKind::scene) != 1) return e;
  const std::uint32_t flags = package.records<SectionKind::scene>()[0].effect_flags;
  const gpu::SceneEffects& r = package.records<SectionKind::effects>()[0];
  if (flags & gpu::NANO_EFFECT_CLIPPING_PLANES) {
    e.clipping_on = true;
    for (std::uint32_t k = 0; k < r.clip_plane_count && k < gpu::NANO_MAX_CLIP_PLANES; ++k)
      e.clipping.planes.push_back(glm::dvec4(r.clip_planes[k]));
    if (r.clip_box_min.w == 1.f) e.clipping.box = {glm::dvec3(r.clip_box_min), glm::dvec3(r.clip_box_max)};
  }
  e.animation_on = flags & gpu::NANO_EFFECT_PROXY_ANIMATION;
  if (flags & gpu::NANO_EFFECT_JITTER) {
    e.jitter_on = true;
    e.jitter_degrees = r.jitter.x;
    e.jitter_hz = r.jitter.y;
  }
  if (flags & gpu::NANO_EFFECT_AMBIENT_OCCLUSION) {
    e.ambient_occlusion_on = true;
    e.ao_rays = std::uint32_t(r.ambient_occlusion.x);
    e.ao_radius = r.ambient_occlusion.y;
  }
  if (flags & gpu::NANO_EFFECT_SHADOWS) {
    e.shadows_on = true;
    e.light_direction = glm::dvec3(r.shadow_light);
  }
  return e;
}

bool& effect_flag(EffectSettings& effects, std::string_view name) {
  if (name == "clipping") return effects.clipping_on;
  if (name == "animation") return effects.animation_on;
  if (name == "jitter") return effects.jitter_on;
  if (name == "ao") return effects.ambient_occlusion_on;
  if (name == "shadows") return effects.shadows_on;
  throw std::invalid_argument("unknown effect '" + std::string(name) + "' (clipping, animation, jitter, ao, shadows)");
}

glm::dvec4 parse_clip_plane(std::string_view text) {
  const std::vector<double> v = numbers(text, 4, "clip plane nx,ny,nz,d");
  const glm::dvec3 n(v[0], v[1], v[2]);
  const double length = glm::length(n);
  if (!(length > 0)) throw std::invalid_argument("clip plane nx,ny,nz,d: the normal must be non-zero, got '" + std::string(text) + "'");
  return glm::dvec4(n / length, v[3] / length);
}

std::pair<glm::dvec3, glm::dvec3> parse_clip_box(std::string_view text) {
  const std::vector<double> v = numbers(text, 6, "clip box x0,y0,z0,x1,y1,z1");
  const glm::dvec3 lo(v[0], v[1], v[2]), hi(v[3], v[4], v[5]);
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
    throw std::invalid_argument("clip box x0,y0,z0,x1,y1,z1: expected x0 < x1, y0 < y1 and z0 < z1, got '" + std::string(text) + "'");
  return {lo, hi};
}

glm::vec3 jitter_frame_parameters(const EffectSettings& e) {
  return {float(e.time), float(glm::radians(e.jitter_degrees)), float(e.jitter_hz)};
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
