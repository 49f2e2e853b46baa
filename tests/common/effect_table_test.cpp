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
    if (e.spec_constant >= 0) EXPECT_TRUE(constants.insert(e.spec_constant).second) << e.name;
    EXPECT_EQ(find_effect(e.name), &e);
    EXPECT_EQ(&effect_declaration(e.id), &e);
  }
  EXPECT_EQ(find_effect("bloom"), nullptr);
  EXPECT_EQ(effect_names(), "clipping, animation, jitter, ao, shadows, outlines");
}

TEST(EffectTable, OptionNamesFollowPrefixAndKey) {
  const EffectDeclaration& ao = effect_declaration(EffectId::ambient_occlusion);
  EXPECT_EQ(parameter_option(ao, ao.parameters[parameter_index(EffectId::ambient_occlusion, "rays")]), "--ao-rays");
  const EffectDeclaration& outlines = effect_declaration(EffectId::outlines);
  EXPECT_EQ(parameter_option(outlines, outlines.parameters[0]), "--outlines-width-pixels");
  EXPECT_THROW(parameter_index(EffectId::shadows, "colour"), std::logic_error);
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

TEST(EffectTable, ParametersRoundTripThroughTheRecordAtTheirSlots) {
  gpu::SceneEffects record{};
  store_parameters(record, EffectId::ambient_occlusion, {glm::dvec3(16, 0, 0), glm::dvec3(12.5, 0, 0)});
  EXPECT_EQ(record.ambient_occlusion, glm::vec4(16, 12.5, 0, 0));  // the slots the 2.1 format documents
  store_parameters(record, EffectId::outlines, {glm::dvec3(3, 0, 0), glm::dvec3(2.5, 0, 0), glm::dvec3(1, 0, 0)});
  EXPECT_EQ(record.outline_width_pixels, 3.f);
  EXPECT_EQ(record.outline_crease_depth, 2.5f);
  EXPECT_EQ(record.outline_colour, 0xff0000ffu);
  const ParameterValues back = load_parameters(record, EffectId::outlines);
  EXPECT_EQ(back[0].x, 3.0);
  EXPECT_EQ(back[1].x, 2.5);
  EXPECT_EQ(back[2], glm::dvec3(1, 0, 0));
  EXPECT_EQ(record.jitter, glm::vec4(0.f));  // nothing else written
  const EffectValues fallbacks = fallback_effect_values();
  EXPECT_EQ(fallbacks[std::size_t(EffectId::ambient_occlusion)][0].x, 8.0);
  EXPECT_EQ(fallbacks[std::size_t(EffectId::outlines)][0].x, 1.0);
}

}  // namespace
}  // namespace nano
