// The effect table: its rows are consistent, and the conversions every layer shares (record slots,
// colours, ranges, option names) round-trip.
#include <cmath>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "common/effect_table.hpp"

namespace nano {
namespace {

TEST(EffectTable, NamesFlagsAndConstantsAreDistinct) {
  std::set<std::string_view> names, keys;
  std::set<std::uint32_t> flags;
  std::set<int> constants;
  for (const EffectDeclaration& e : effect_table()) {
    EXPECT_TRUE(names.insert(e.name).second) << e.name;
    EXPECT_TRUE(keys.insert(e.scene_key).second) << e.scene_key;
    EXPECT_TRUE(flags.insert(e.package_flag).second) << e.name;
    EXPECT_EQ(e.package_flag & (e.package_flag - 1), 0u) << e.name << ": one bit";
    if (e.spec_constant >= 0) {
      EXPECT_TRUE(constants.insert(e.spec_constant).second) << e.name;
    }
    EXPECT_EQ(find_effect(e.name), &e);
    EXPECT_EQ(&effect_declaration(e.id), &e);
  }
  EXPECT_EQ(find_effect("bloom"), nullptr);
  EXPECT_EQ(effect_names(), "clipping, animation, jitter, ao, shadows, outlines, fog");
}

TEST(EffectTable, OptionNamesFollowPrefixAndKey) {
  const EffectDeclaration& ao = effect_declaration(EffectId::ambient_occlusion);
  EXPECT_EQ(parameter_option(ao, effect_parameter(EffectId::ambient_occlusion, "rays")), "--ao-rays");
  const EffectDeclaration& outlines = effect_declaration(EffectId::outlines);
  EXPECT_EQ(parameter_option(outlines, outlines.parameters[0]), "--outlines-width-pixels");
  EXPECT_THROW((void)effect_parameter(EffectId::shadows, "colour"), std::logic_error);
}

TEST(EffectTable, RangesAcceptTheBoundsTheyNameAndNothingBeyond) {
  const EffectParameter& rays = effect_declaration(EffectId::ambient_occlusion).parameters[0];
  EXPECT_EQ(parameter_problem(rays, {1, 0, 0}), "");
  EXPECT_EQ(parameter_problem(rays, {1024, 0, 0}), "");
  EXPECT_NE(parameter_problem(rays, {0, 0, 0}), "");
  EXPECT_NE(parameter_problem(rays, {1025, 0, 0}), "");
  EXPECT_NE(parameter_problem(rays, {2.5, 0, 0}), "");
  const EffectParameter& radius = effect_declaration(EffectId::ambient_occlusion).parameters[1];
  EXPECT_NE(parameter_problem(radius, {0, 0, 0}), "");  // exclusive minimum
  EXPECT_EQ(parameter_problem(radius, {1e30, 0, 0}), "");
  EXPECT_NE(parameter_problem(radius, {NAN, 0, 0}), "");
  const EffectParameter& light = effect_declaration(EffectId::shadows).parameters[0];
  EXPECT_NE(parameter_problem(light, {0, 0, 0}), "");
  const EffectParameter& colour = effect_declaration(EffectId::outlines).parameters[2];
  EXPECT_EQ(parameter_problem(colour, {0, 0.5, 1}), "");
  EXPECT_NE(parameter_problem(colour, {0, 1.01, 0}), "");
}

TEST(EffectTable, ColoursPackToRgba8) {
  EXPECT_EQ(pack_colour({0, 0, 0}), 0xff000000u);
  EXPECT_EQ(pack_colour({1, 0, 1}), 0xffff00ffu);
  EXPECT_EQ(pack_colour({0.5, 0.25, 1}), 0xffff4080u);  // 127.5 and 63.75 round to 128 and 64
  EXPECT_EQ(unpack_colour(0xffff00ffu), glm::dvec3(1, 0, 1));
}

// Each parameter's slot is the member of gpu::SceneEffects (the struct render.comp reads) that the
// format documents, typed as the member is; nothing else of the record is written.
TEST(EffectTable, ParametersLandAtTheirMembers) {
  gpu::SceneEffects record{};
  set_parameter(record, effect_parameter(EffectId::ambient_occlusion, "rays"), glm::dvec3(16, 0, 0));
  number_slot(record, effect_parameter(EffectId::ambient_occlusion, "radius")) = 12.5f;
  EXPECT_EQ(record.ambient_occlusion, glm::vec2(16, 12.5));  // the slots the 2.1 format documents
  number_slot(record, effect_parameter(EffectId::outlines, "width_pixels")) = 3;
  set_parameter(record, effect_parameter(EffectId::outlines, "crease_depth"), glm::dvec3(2.5, 0, 0));
  set_parameter(record, effect_parameter(EffectId::outlines, "colour"), glm::dvec3(1, 0, 0));
  EXPECT_EQ(record.outline_width_pixels, 3.f);
  EXPECT_EQ(record.outline_crease_depth, 2.5f);
  EXPECT_EQ(record.outline_colour, 0xff0000ffu);
  EXPECT_EQ(colour_slot(record, effect_parameter(EffectId::outlines, "colour")), 0xff0000ffu);
  set_parameter(record, effect_parameter(EffectId::shadows, "light_direction"), glm::dvec3(0, 0.6, 0.8));
  EXPECT_EQ(&direction_slot(record, effect_parameter(EffectId::shadows, "light_direction")), &record.shadow_light);
  EXPECT_EQ(record.jitter, glm::vec2(0.f));  // nothing else written
  EXPECT_EQ(record.ao_radius_pixels, 0.f);
  EXPECT_EQ(record.fog_range, glm::vec2(0.f));
  // A slot is read as its kind only.
  EXPECT_THROW((void)number_slot(record, effect_parameter(EffectId::outlines, "colour")), std::logic_error);
  EXPECT_THROW((void)direction_slot(record, effect_parameter(EffectId::fog, "start")), std::logic_error);
  const gpu::SceneEffects fallbacks = fallback_effect_record();
  EXPECT_EQ(fallbacks.ambient_occlusion, glm::vec2(8, 40));
  EXPECT_EQ(fallbacks.outline_width_pixels, 1.f);
  EXPECT_EQ(fallbacks.outline_colour, 0xff000000u);
  EXPECT_EQ(fallbacks.clip_plane_count, 0u);
  // copy_parameters moves one effect's slots and nothing else.
  gpu::SceneEffects copy{};
  copy_parameters(copy, record, EffectId::outlines);
  EXPECT_EQ(copy.outline_width_pixels, 3.f);
  EXPECT_EQ(copy.outline_colour, 0xff0000ffu);
  EXPECT_EQ(copy.ambient_occlusion, glm::vec2(0.f));
}

// Every preset names distinct effects that take parameters, each value accepted by the table's range.
TEST(EffectTable, PresetsHoldValuesTheTableAccepts) {
  ASSERT_FALSE(effect_presets().empty());
  for (const EffectPreset& preset : effect_presets()) {
    EXPECT_EQ(find_preset(preset.name), &preset);
    std::array<bool, kEffectCount> seen{};
    for (const PresetEffect& effect : preset.effects) {
      const EffectDeclaration& declaration = effect_declaration(effect.id);
      EXPECT_FALSE(seen[std::size_t(effect.id)]) << preset.name << " names " << declaration.name << " twice";
      seen[std::size_t(effect.id)] = true;
      EXPECT_FALSE(declaration.parameters.empty());
      for (std::size_t i = 0; i < declaration.parameters.size(); ++i)
        EXPECT_EQ(parameter_problem(declaration.parameters[i], effect.values[i]), "") << preset.name << " " << declaration.name;
      for (std::size_t i = declaration.parameters.size(); i < kMaxEffectParameters; ++i) EXPECT_EQ(effect.values[i], glm::dvec3(0));
    }
  }
  EXPECT_EQ(find_preset("goodsell"), nullptr);
  EXPECT_EQ(preset_names(), "illustrative");
}

// The new parameters sit in words older formats kept zero: each at its member of gpu::SceneEffects.
TEST(EffectTable, FogAndScaleParametersAtTheirMembers) {
  gpu::SceneEffects record{};
  set_parameter(record, effect_parameter(EffectId::fog, "start"), glm::dvec3(0.5, 0, 0));
  set_parameter(record, effect_parameter(EffectId::fog, "span"), glm::dvec3(2, 0, 0));
  set_parameter(record, effect_parameter(EffectId::fog, "strength"), glm::dvec3(0.25, 0, 0));
  EXPECT_EQ(record.fog_range, glm::vec2(0.5, 2));
  EXPECT_EQ(record.fog_strength, 0.25f);
  set_parameter(record, effect_parameter(EffectId::ambient_occlusion, "radius_pixels"), glm::dvec3(6, 0, 0));
  EXPECT_EQ(record.ao_radius_pixels, 6.f);
  set_parameter(record, effect_parameter(EffectId::outlines, "fade_pixels"), glm::dvec3(9, 0, 0));
  EXPECT_EQ(record.outline_fade_pixels, 9.f);
}

}  // namespace
}  // namespace nano
