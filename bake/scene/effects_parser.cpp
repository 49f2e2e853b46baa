#include "bake/scene/effects_parser.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include <glm/geometric.hpp>

#include "bake/scene/transform_parser.hpp"

namespace nano::scene {
namespace {

// Stored with a unit normal, so that n·p + d is a signed distance in Å.
glm::dvec4 parse_plane(const JsonCursor& c) {
  const glm::dvec4 p = c.vec4();
  const glm::dvec3 normal(p);
  if (normal == glm::dvec3(0.0)) c.fail("the plane normal [nx, ny, nz] must be non-zero, got " + c.shown());
  // n and d scaled alike (by the power of two of `rescaled_by_power_of_two`), then divided by |n|.
  const int e = std::ilogb(std::max({std::abs(normal.x), std::abs(normal.y), std::abs(normal.z)}));
  const glm::dvec3 n = rescaled_by_power_of_two(normal);
  const double length = glm::length(n);
  const glm::dvec4 plane(n / length, std::ldexp(p.w, -e) / length);
  if (!std::isfinite(plane.w)) c.fail("the plane's offset d / |n| is beyond a double, got " + c.shown());
  return plane;
}

Clipping parse_clipping(const JsonCursor& c) {
  c.only_keys({"planes", "box"});
  if (!c.has("planes") && !c.has("box")) c.fail("expected \"planes\", \"box\" or both");
  Clipping clipping;
  if (const auto planes = c.optional("planes")) {
    for (const JsonCursor& plane : planes->elements(1)) clipping.planes.push_back(parse_plane(plane));
    // The package and the shader hold at most 8 (NANO_MAX_CLIP_PLANES); the box comes on top.
    if (clipping.planes.size() > 8) planes->fail("at most 8 planes, got " + std::to_string(clipping.planes.size()));
  }
  if (const auto box = c.optional("box")) clipping.box = parse_box(*box);
  return clipping;
}

SteadyMotion parse_steady_motion(const JsonCursor& c) {
  c.only_keys({"spin_axis", "spin_degrees_per_second", "velocity"});
  if (!c.has("spin_degrees_per_second") && !c.has("velocity"))
    c.fail("expected \"spin_degrees_per_second\", \"velocity\" or both");
  SteadyMotion m;
  if (const auto axis = c.optional("spin_axis")) m.spin_axis = axis->unit_vec3();
  if (const auto spin = c.optional("spin_degrees_per_second")) m.spin_degrees_per_second = spin->number();
  if (const auto velocity = c.optional("velocity")) m.velocity = velocity->vec3();
  return m;
}

std::vector<InstanceKeyframes> parse_keyframes(const JsonCursor& c, std::size_t instance_count) {
  std::vector<InstanceKeyframes> all;
  std::set<std::size_t> seen;
  for (const JsonCursor& track : c.elements(1)) {
    track.only_keys({"instance", "keys"});
    const JsonCursor index = track.required("instance");
    if (instance_count == 0) index.fail("the scene has no instances to animate");
    InstanceKeyframes k;
    k.instance = static_cast<std::size_t>(index.integer_between(0, static_cast<std::int64_t>(instance_count) - 1));
    if (!seen.insert(k.instance).second)
      index.fail("instance " + std::to_string(k.instance) + " already has keyframes");
    for (const JsonCursor& key : track.required("keys").elements(1)) {
      key.only_keys({"time", "transform", "matrix"});
      const JsonCursor time = key.required("time");
      Keyframe frame{time.number_at_least(0.0), parse_placement_transform(key)};
      if (!k.keys.empty() && !(frame.time > k.keys.back().time))
        time.fail("keyframe times must increase strictly, got " + time.shown() + " after " +
                  std::to_string(k.keys.back().time));
      k.keys.push_back(frame);
    }
    all.push_back(std::move(k));
  }
  return all;
}

// A plain effect (common/effect_table.hpp): each parameter by its kind and range, written at its slot
// of `record`; an absent one keeps what `record` holds when `under_preset` (then none is required),
// else takes the table's fallback.
void parse_plain_effect(const JsonCursor& c, const EffectDeclaration& effect, gpu::SceneEffects& record, bool under_preset = false) {
  std::array<std::string_view, kMaxEffectParameters> keys{};
  for (std::size_t i = 0; i < effect.parameters.size(); ++i) keys[i] = effect.parameters[i].key;
  c.only_keys(std::span<const std::string_view>(keys.data(), effect.parameters.size()));
  for (const EffectParameter& p : effect.parameters) {
    if (!under_preset) set_parameter(record, p, p.fallback);
    const std::optional<JsonCursor> field = p.required && !under_preset ? std::optional(c.required(p.key)) : c.optional(p.key);
    if (!field) continue;
    glm::dvec3 value(0.0);
    switch (p.kind) {
      case ParameterKind::whole_number:
        value.x = double(field->integer_between(std::int64_t(p.min), std::int64_t(p.max)));
        break;
      case ParameterKind::number:
        if (std::isinf(p.max)) value.x = p.min_exclusive ? field->number_greater_than(p.min) : field->number_at_least(p.min);
        else if (!p.min_exclusive) value.x = field->number_between(p.min, p.max);
        else value.x = field->number_greater_than(p.min);
        break;
      case ParameterKind::unit_vector: value = field->unit_vec3(); break;
      case ParameterKind::colour: value = field->vec3(); break;
    }
    if (const std::string problem = parameter_problem(p, value); !problem.empty())
      field->fail("expected a value that " + problem + ", got " + field->shown());
    set_parameter(record, p, value);
  }
}

// Validated in full even when disabled, so a typo never hides behind "enabled": false. The jitter
// inside it is a plain effect; it is parsed here so that "enabled": false turns it off as well.
std::optional<Animation> parse_animation(const JsonCursor& c, std::size_t instance_count, Effects& effects) {
  c.only_keys({"enabled", "proxy_motion", "jitter"});
  const bool enabled = c.has("enabled") ? c.required("enabled").boolean() : true;
  Animation a;
  if (const auto motion = c.optional("proxy_motion")) {
    motion->only_keys({"steady", "keyframes"});
    const bool steady = motion->has("steady"), keyed = motion->has("keyframes");
    if (steady == keyed) motion->fail("expected exactly one of \"steady\" and \"keyframes\"");
    if (steady) a.steady = parse_steady_motion(motion->required("steady"));
    else a.keyframes = parse_keyframes(motion->required("keyframes"), instance_count);
  }
  if (const auto jitter = c.optional("jitter")) {
    gpu::SceneEffects disabled{};  // checked, then dropped
    parse_plain_effect(*jitter, effect_declaration(EffectId::jitter), enabled ? effects.parameters : disabled);
    if (enabled) effects.plain[static_cast<std::size_t>(EffectId::jitter)] = true;
  }
  if (!c.has("proxy_motion") && !c.has("jitter")) c.fail("expected \"proxy_motion\", \"jitter\" or both");
  if (!enabled) return std::nullopt;
  return a;
}

}  // namespace

Box parse_box(const JsonCursor& c) {
  const auto corners = c.elements();
  if (corners.size() != 2) c.fail("expected [[xmin, ymin, zmin], [xmax, ymax, zmax]], got " + c.shown());
  const Box box{corners[0].vec3(), corners[1].vec3()};
  if (!(box.min.x < box.max.x && box.min.y < box.max.y && box.min.z < box.max.z))
    c.fail("expected min < max on every axis, got " + c.shown());
  const glm::dvec3 size = box.max - box.min;
  if (!std::isfinite(size.x) || !std::isfinite(size.y) || !std::isfinite(size.z))
    c.fail("the box is larger than a double can measure (max - min overflows), got " + c.shown());
  return box;
}

Effects parse_effects(const JsonCursor& c, std::size_t instance_count) {
  // The keys directly under "effects": every table row whose key is not nested in another's.
  std::array<std::string_view, kEffectCount + 1> keys{};
  std::size_t key_count = 0;
  for (const EffectDeclaration& effect : effect_table())
    if (effect.scene_key.find('.') == std::string_view::npos) keys[key_count++] = effect.scene_key;
  keys[key_count++] = "preset";
  c.only_keys(std::span<const std::string_view>(keys.data(), key_count));
  Effects e;
  // A preset's effects first; an effect the scene also writes keeps the preset's values for the keys
  // it leaves out.
  if (const auto preset = c.optional("preset")) {
    const std::string name = preset->string();
    const EffectPreset* found = find_preset(name);
    if (!found) preset->fail("unknown preset \"" + name + "\" (" + preset_names() + ")");
    for (const PresetEffect& effect : found->effects) {
      e.plain[static_cast<std::size_t>(effect.id)] = true;
      set_preset_parameters(e.parameters, effect);
    }
  }
  if (const auto clipping = c.optional("clipping")) e.clipping = parse_clipping(*clipping);
  if (const auto animation = c.optional("animation")) e.animation = parse_animation(*animation, instance_count, e);
  for (const EffectDeclaration& effect : effect_table()) {
    if (!effect.structured.empty() || effect.scene_key.find('.') != std::string_view::npos) continue;
    if (const auto object = c.optional(effect.scene_key)) {
      parse_plain_effect(*object, effect, e.parameters, e.sets(effect.id));
      e.plain[static_cast<std::size_t>(effect.id)] = true;
    }
  }
  return e;
}

Camera parse_camera(const JsonCursor& c) {
  c.only_keys({"position", "look_at", "up", "fov_degrees"});
  Camera cam;  // fov_degrees: kDefaultFovDegrees unless given
  cam.position = c.required("position").vec3();
  const JsonCursor look_at = c.required("look_at");
  cam.look_at = look_at.vec3();
  if (cam.look_at == cam.position) look_at.fail("look_at must differ from position");
  const glm::dvec3 towards = cam.look_at - cam.position;  // not 0: IEEE subtraction of distinct numbers never is
  if (!std::isfinite(towards.x) || !std::isfinite(towards.y) || !std::isfinite(towards.z))
    look_at.fail("look_at is too far from position: look_at - position overflows a double");
  const auto up = c.optional("up");
  if (up) cam.up = up->unit_vec3();
  const glm::dvec3 view = glm::normalize(rescaled_by_power_of_two(towards));
  // Nearly parallel up and view directions leave the camera's roll undefined.
  if (glm::length(glm::cross(view, cam.up)) < 1e-6) {
    if (up) up->fail("up must not be parallel to the view direction");
    c.fail("the view direction is parallel to the default up [0, 1, 0]; give \"up\"");
  }
  if (const auto fov = c.optional("fov_degrees")) cam.fov_degrees = fov->number_strictly_between(0.0, 180.0);
  return cam;
}

}  // namespace nano::scene
