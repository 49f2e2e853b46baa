#include "bake/scene/effects_parser.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/scene/input_error_matchers.hpp"

namespace nano::scene {
namespace {

const std::string file = "scene.json";

Effects effects_from(const char* text, std::size_t instance_count = 3) {
  const Json doc = parse_json_text(text, file);
  return parse_effects(JsonCursor(doc, file).required("effects"), instance_count);
}

// A parameter as the package's effects record holds it.
float number(const Effects& e, EffectId id, std::string_view key) { return number_slot(e.parameters, effect_parameter(id, key)); }

Camera camera_from(const char* text) {
  const Json doc = parse_json_text(text, file);
  return parse_camera(JsonCursor(doc, file).required("camera"));
}

TEST(EffectsParser, NothingGivenIsAllOff) {
  EXPECT_EQ(effects_from(R"({"effects": {}})"), Effects{});
}

TEST(EffectsParser, SteadyMotion) {
  const Effects e = effects_from(R"({"effects": {"animation": {"proxy_motion": {"steady":
      {"spin_axis": [0, 3, 4], "spin_degrees_per_second": 12, "velocity": [1, 2, 3]}}}}})");
  ASSERT_TRUE(e.animation.has_value());
  EXPECT_EQ(e.animation->steady, (SteadyMotion{{0, 0.6, 0.8}, 12.0, {1, 2, 3}}));
  EXPECT_TRUE(e.animation->keyframes.empty());
  EXPECT_FALSE(e.sets(EffectId::jitter));
  // Velocity alone keeps the default axis and no spin.
  const Effects drift = effects_from(R"({"effects": {"animation": {"proxy_motion": {"steady": {"velocity": [5, 0, 0]}}}}})");
  EXPECT_EQ(drift.animation->steady, (SteadyMotion{{0, 0, 1}, 0.0, {5, 0, 0}}));
}

TEST(EffectsParser, DisabledAnimationIsOffButStillChecked) {
  EXPECT_FALSE(effects_from(R"({"effects": {"animation": {"enabled": false,
      "jitter": {"amplitude_degrees": 3, "frequency_hz": 1}}}})").animation.has_value());
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"animation": {"enabled": false,
      "jitter": {"amplitude_degrees": 3, "frequncy_hz": 1}}}})"),
                     "effects.animation.jitter.frequncy_hz", "unknown key");
}

TEST(EffectsParser, AnimationRules) {
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"animation": {}}})"), "effects.animation",
                     "expected \"proxy_motion\", \"jitter\" or both");
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"animation": {"proxy_motion": {}}}})"), "effects.animation.proxy_motion",
                     "exactly one of \"steady\" and \"keyframes\"");
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"animation": {"proxy_motion": {"steady": {"spin_axis": [1, 0, 0]}}}}})"),
                     "effects.animation.proxy_motion.steady", "\"spin_degrees_per_second\", \"velocity\" or both");
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"animation": {"jitter": {"amplitude_degrees": 0.5, "frequency_hz": 0}}}})"),
                     "effects.animation.jitter.frequency_hz", "> 0");
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"animation": {"jitter": {"amplitude_degrees": 181, "frequency_hz": 1}}}})"),
                     "effects.animation.jitter.amplitude_degrees", "[0, 180]");
}

TEST(EffectsParser, KeyframeRules) {
  const char* prefix = R"({"effects": {"animation": {"proxy_motion": {"keyframes": )";
  auto with = [&](const std::string& keyframes) { return effects_from((prefix + keyframes + "}}}}").c_str()); };
  const Effects ok = with(R"([{"instance": 2, "keys": [{"time": 1, "transform": {"translate": [1, 2, 3]}}]}])");
  EXPECT_EQ(ok.animation->keyframes,
            (std::vector<InstanceKeyframes>{{2, {{1.0, {glm::dvec4(1, 0, 0, 1), glm::dvec4(0, 1, 0, 2), glm::dvec4(0, 0, 1, 3)}}}}}));
  EXPECT_INPUT_ERROR(with(R"([{"instance": 3, "keys": [{"time": 0}]}])"),
                     "effects.animation.proxy_motion.keyframes[0].instance", "expected an integer in [0, 2], got 3");
  EXPECT_INPUT_ERROR(with(R"([{"instance": 0, "keys": [{"time": 1}, {"time": 1}]}])"),
                     "effects.animation.proxy_motion.keyframes[0].keys[1].time", "increase strictly");
  EXPECT_INPUT_ERROR(with(R"([{"instance": 0, "keys": [{"time": -1}]}])"),
                     "effects.animation.proxy_motion.keyframes[0].keys[0].time", ">= 0");
  EXPECT_INPUT_ERROR(with(R"([{"instance": 1, "keys": [{"time": 0}]}, {"instance": 1, "keys": [{"time": 0}]}])"),
                     "effects.animation.proxy_motion.keyframes[1].instance", "already has keyframes");
  EXPECT_INPUT_ERROR(with(R"([{"instance": 0, "keys": []}])"), "effects.animation.proxy_motion.keyframes[0].keys",
                     "at least 1 element");
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"clipping": {"planes": [[1,0,0,0],[1,0,0,0],[1,0,0,0],[1,0,0,0],
                     [1,0,0,0],[1,0,0,0],[1,0,0,0],[1,0,0,0],[1,0,0,0]]}}})"), "effects.clipping.planes", "at most 8 planes, got 9");
  EXPECT_INPUT_ERROR(with(R"([{"instance": 0, "keys": [{"time": 0, "matrix": [[0, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}]}])"),
                     "effects.animation.proxy_motion.keyframes[0].keys[0].matrix", "positive determinant");
}

TEST(EffectsParser, ClippingAmbientOcclusionShadows) {
  const Effects e = effects_from(R"({"effects": {
      "clipping": {"planes": [[3, 0, 4, 10], [0, -2, 0, 0]]},
      "ambient_occlusion": {"rays": 16, "radius": 12.5},
      "shadows": {"light_direction": [1, 1, 0]}}})");
  EXPECT_EQ(e.clipping, (Clipping{{glm::dvec4(0.6, 0, 0.8, 2), glm::dvec4(0, -1, 0, 0)}, std::nullopt}));
  ASSERT_TRUE(e.sets(EffectId::ambient_occlusion));
  EXPECT_EQ(number(e, EffectId::ambient_occlusion, "rays"), 16.f);
  EXPECT_EQ(number(e, EffectId::ambient_occlusion, "radius"), 12.5f);
  ASSERT_TRUE(e.sets(EffectId::shadows));
  EXPECT_EQ(e.parameters.shadow_light, glm::vec3(float(std::sqrt(0.5)), float(std::sqrt(0.5)), 0.f));  // normalised in double
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"clipping": {}}})"), "effects.clipping", "\"planes\", \"box\" or both");
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"clipping": {"planes": []}}})"), "effects.clipping.planes",
                     "at least 1 element");
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"ambient_occlusion": {"rays": 0, "radius": 1}}})"),
                     "effects.ambient_occlusion.rays", "[1, 1024]");
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"ambient_occlusion": {"rays": 4}}})"), "effects.ambient_occlusion.radius",
                     "missing required key");
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"shadows": {"light_direction": [0, 0, 0]}}})"),
                     "effects.shadows.light_direction", "non-zero");
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"bloom": {}}})"), "effects.bloom", "unknown key");
}

TEST(EffectsParser, FogTakesTheTableFallbacksAndRanges) {
  const Effects e = effects_from(R"({"effects": {"fog": {"strength": 0.5}}})");
  ASSERT_TRUE(e.sets(EffectId::fog));
  EXPECT_EQ(number(e, EffectId::fog, "start"), 0.f);  // the nearest depth the frame shows
  EXPECT_EQ(number(e, EffectId::fog, "span"), 1.f);   // the whole depth range
  EXPECT_EQ(number(e, EffectId::fog, "strength"), 0.5f);
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"fog": {"span": 0}}})"), "effects.fog.span", "> 0");
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"fog": {"strength": 1.5}}})"), "effects.fog.strength", "[0, 1]");
}

// The preset turns its effects on with its values; what the scene writes beside it wins, key by key,
// and an effect's required keys are no longer required under a preset.
TEST(EffectsParser, PresetThenTheScenesOwnKeys) {
  const Effects plain = effects_from(R"({"effects": {"preset": "illustrative"}})");
  const EffectPreset& preset = *find_preset("illustrative");
  gpu::SceneEffects expected{};
  for (const PresetEffect& effect : preset.effects) {
    EXPECT_TRUE(plain.sets(effect.id)) << effect_declaration(effect.id).name;
    set_preset_parameters(expected, effect);
  }
  EXPECT_EQ(plain.parameters, expected);
  EXPECT_EQ(plain.parameters.outline_fade_pixels, 12.f);
  EXPECT_FALSE(plain.sets(EffectId::shadows));
  const Effects tuned = effects_from(R"({"effects": {"preset": "illustrative", "outlines": {"width_pixels": 2},
                                                     "ambient_occlusion": {"rays": 4}, "shadows": {"light_direction": [0, 1, 0]}}})");
  EXPECT_EQ(tuned.parameters.outline_width_pixels, 2.f);
  EXPECT_EQ(tuned.parameters.outline_crease_depth, plain.parameters.outline_crease_depth);
  EXPECT_EQ(tuned.parameters.outline_fade_pixels, plain.parameters.outline_fade_pixels);
  EXPECT_EQ(number(tuned, EffectId::ambient_occlusion, "rays"), 4.f);
  EXPECT_EQ(number(tuned, EffectId::ambient_occlusion, "radius"), number(plain, EffectId::ambient_occlusion, "radius"));
  EXPECT_TRUE(tuned.sets(EffectId::shadows));
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"preset": "ilustrative"}})"), "effects.preset", "unknown preset \"ilustrative\" (illustrative)");
  EXPECT_INPUT_ERROR(effects_from(R"({"effects": {"preset": 3}})"), "effects.preset", "string");
}

TEST(EffectsParser, Box) {
  const Json doc = parse_json_text(R"({"ok": [[-1, 0, 2], [1, 5, 3]], "flat": [[0, 0, 0], [1, 0, 1]], "short": [[0, 0, 0]]})", file);
  const JsonCursor root(doc, file);
  EXPECT_EQ(parse_box(root.required("ok")), (Box{{-1, 0, 2}, {1, 5, 3}}));
  EXPECT_INPUT_ERROR(parse_box(root.required("flat")), "flat", "min < max on every axis");
  EXPECT_INPUT_ERROR(parse_box(root.required("short")), "short", "[[xmin, ymin, zmin], [xmax, ymax, zmax]]");
}

TEST(EffectsParser, Camera) {
  EXPECT_EQ(camera_from(R"({"camera": {"position": [1, 2, 3], "look_at": [1, 2, 0]}})"),
            (Camera{{1, 2, 3}, {1, 2, 0}, {0, 1, 0}, 45.0}));
  EXPECT_EQ(camera_from(R"({"camera": {"position": [0, 5, 0], "look_at": [0, 0, 0], "up": [0, 0, -2], "fov_degrees": 30}})"),
            (Camera{{0, 5, 0}, {0, 0, 0}, {0, 0, -1}, 30.0}));
  EXPECT_INPUT_ERROR(camera_from(R"({"camera": {"position": [1, 1, 1], "look_at": [1, 1, 1]}})"), "camera.look_at",
                     "must differ from position");
  EXPECT_INPUT_ERROR(camera_from(R"({"camera": {"position": [0, 5, 0], "look_at": [0, 0, 0]}})"), "camera",
                     "parallel to the default up");
  EXPECT_INPUT_ERROR(camera_from(R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 0, 1]}})"),
                     "camera.up", "parallel to the view direction");
  EXPECT_INPUT_ERROR(camera_from(R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov_degrees": 0}})"),
                     "camera.fov_degrees", "(0, 180)");
}

}  // namespace
}  // namespace nano::scene
