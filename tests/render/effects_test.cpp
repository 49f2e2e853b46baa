// Scene effects on the host and in the shared shader math: the package's effects read back, the CLI
// and script syntax of clip planes and boxes, animation poses against analytic rigid motions, and
// the jitter / ray-offset / sampling functions of shared/effects.h.
#include <cmath>
#include <cstddef>
#include <cstring>
#include <set>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "format/validator.hpp"
#include "runtime/render/animation.hpp"
#include "runtime/render/effects.hpp"
#include "shared/effects.h"
#include "shared/render_scene.h"
#include "tests/format/sample_scene.hpp"
#include "tests/scene/input_error_matchers.hpp"

namespace {

using namespace nano;
using namespace nano::render;
using glm::dvec3;
using nano::scene::testing::expect_input_error;

struct Opened {
  explicit Opened(const format::test::SampleScene& s)
      : package(format::Package::from_bytes(format::test::build(s, format::Compression::none), "effects.nup")) {
    format::validate_semantics(package);
  }
  format::Package package;
};

TEST(PackageEffects, ReadsWhatTheSectionsHold) {
  const Opened p(format::test::make_sample_scene());
  const EffectSettings e = package_effects(p.package);
  EXPECT_TRUE(e.flag(EffectId::clipping));
  ASSERT_EQ(e.clipping.planes.size(), 1u);
  EXPECT_EQ(e.clipping.planes[0], glm::dvec4(0, 0, 1, -2));
  ASSERT_TRUE(e.clipping.box.has_value());
  EXPECT_EQ(e.clipping.box->first, dvec3(-10, -10, -10));
  EXPECT_EQ(e.clipping.box->second, dvec3(60, 10, 10));
  EXPECT_TRUE(e.flag(EffectId::animation));
  EXPECT_FALSE(e.flag(EffectId::jitter));
  EXPECT_TRUE(e.flag(EffectId::ambient_occlusion));
  EXPECT_EQ(e.ao_rays(), 8u);
  EXPECT_EQ(e.ao_radius(), 40.f);
  EXPECT_TRUE(e.flag(EffectId::shadows));
  EXPECT_NEAR(e.light_direction().y, 0.6, 1e-7);
}

// One record from the package to the shader: the package's outline parameters are what the settings
// hold, an edit by name through the table lands in the frame's record at the std430 offset
// render.comp reads (docs/format.md, section "effects": outline_width_pixels at byte 244), and an
// effect switched off reaches the shader as zeros while the settings keep its values.
TEST(PackageEffects, OneRecordFromThePackageToTheFrame) {
  format::test::SampleScene s = format::test::make_sample_scene();
  s.scene[0].effect_flags |= package_flag(EffectId::outlines);
  s.effects[0].outline_width_pixels = 2;
  s.effects[0].outline_crease_depth = 7.5f;
  s.effects[0].outline_colour = 0xff0000ffu;
  s.effects[0].outline_fade_pixels = 4;
  const Opened p(s);
  EffectSettings e = package_effects(p.package);
  ASSERT_TRUE(e.flag(EffectId::outlines));
  EXPECT_EQ(e.number(EffectId::outlines, "width_pixels"), 2.f);
  EXPECT_EQ(e.number(EffectId::outlines, "crease_depth"), 7.5f);
  EXPECT_EQ(colour_slot(e.record, effect_parameter(EffectId::outlines, "colour")), 0xff0000ffu);
  EXPECT_EQ(e.number(EffectId::fog, "strength"), 0.6f);  // off in the package: the table's fallback

  parse_parameter(e.record, effect_parameter(EffectId::outlines, "width_pixels"), "5", "--outlines-width-pixels");
  e.number(EffectId::outlines, "fade_pixels") = 9;  // as the panel's slider writes it
  gpu::RenderFrame frame{};
  frame.effect_record = effect_record(e);
  const auto word_at = [&](std::size_t record_byte) {
    float x;
    std::memcpy(&x, reinterpret_cast<const unsigned char*>(&frame) + offsetof(gpu::RenderFrame, effect_record) + record_byte, 4);
    return x;
  };
  EXPECT_EQ(word_at(244), 5.f);    // outline_width_pixels
  EXPECT_EQ(word_at(248), 7.5f);   // outline_crease_depth, the package's
  EXPECT_EQ(word_at(236), 9.f);    // outline_fade_pixels
  EXPECT_EQ(word_at(208), 8.f);    // ambient_occlusion.x: rays, on in the package
  EXPECT_EQ(word_at(220), 0.f);    // fog_strength: fog is off
  EXPECT_EQ(frame.effect_record.clip_plane_count, 0u);  // clipping reaches the shader as RenderFrame::clip

  e.flag(EffectId::outlines) = false;
  EXPECT_EQ(effect_record(e).outline_width_pixels, 0.f);
  EXPECT_EQ(e.number(EffectId::outlines, "width_pixels"), 5.f);  // kept for when it is switched on again
}

TEST(PackageEffects, AllOffWithoutTheSection) {
  format::test::SampleScene s = format::test::make_sample_scene();
  s.effects.clear();
  s.keyframes.clear();
  const Opened p(s);
  const EffectSettings e = package_effects(p.package);
  EXPECT_FALSE(e.flag(EffectId::clipping) || e.flag(EffectId::animation) || e.flag(EffectId::jitter) || e.flag(EffectId::ambient_occlusion) || e.flag(EffectId::shadows));
  // Without effects the instances stand where the package puts them, at any time.
  const auto t = animated_instance_transforms(p.package, 5.0);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[1].translation, dvec3(50, 0, -5));
}

TEST(ClipSyntax, PlanesAndBoxes) {
  EXPECT_EQ(parse_clip_plane("0,0,2,-4", "--clip-plane"), glm::dvec4(0, 0, 1, -2));  // normalised: d in Å
  EXPECT_EQ(parse_clip_plane(" 1, 0,0, 5", "--clip-plane"), glm::dvec4(1, 0, 0, 5));
  for (const char* wrong : {"0,0,0,1", "1,0,0", "1,0,0,1,2", "1,0,x,1", "1,0,nan,1"}) {
    const InputError e = expect_input_error([&] { (void)parse_clip_plane(wrong, {"clip.nvs", "line 4"}); });
    EXPECT_EQ(std::string(e.what()).rfind("clip.nvs:line 4: clip plane nx,ny,nz,d: ", 0), 0u) << e.what();
  }
  const auto box = parse_clip_box("-1,-2,-3,4,5,6", "--clip-box");
  EXPECT_EQ(box.first, dvec3(-1, -2, -3));
  EXPECT_EQ(box.second, dvec3(4, 5, 6));
  const InputError e = expect_input_error([] { (void)parse_clip_box("1,0,0,0,1,1", "--clip-box"); });
  EXPECT_EQ(e.file(), "--clip-box") << e.what();
}

TEST(ClipHalfSpaces, BoxFacesKeepExactlyTheInside) {
  Clipping c;
  c.planes.push_back(glm::dvec4(0, 0, 3, 0));
  c.box = {dvec3(-1, -2, -3), dvec3(4, 5, 6)};
  const auto h = clip_half_spaces(c);
  ASSERT_EQ(h.size(), 7u);
  EXPECT_EQ(h[0], glm::dvec4(0, 0, 1, 0));
  const auto kept = [&](dvec3 p) {
    for (const auto& s : h)
      if (glm::dot(dvec3(s), p) + s.w < 0) return false;
    return true;
  };
  EXPECT_TRUE(kept(dvec3(0, 0, 1)));
  EXPECT_TRUE(kept(dvec3(4, 5, 6)));    // closed box
  EXPECT_FALSE(kept(dvec3(0, 0, -0.1)));  // the plane
  EXPECT_FALSE(kept(dvec3(4.01, 0, 1)));
  EXPECT_FALSE(kept(dvec3(0, -2.01, 1)));
  EXPECT_FALSE(kept(dvec3(0, 0, 6.01)));
}

TEST(SetEffect, NamesAndDefaults) {
  EffectSettings e;
  for (const EffectDeclaration& effect : effect_table()) set_effect(e, effect.name, true, "--effect");
  EXPECT_TRUE(e.flag(EffectId::clipping) && e.flag(EffectId::animation) && e.flag(EffectId::jitter) && e.flag(EffectId::ambient_occlusion) && e.flag(EffectId::shadows));
  EXPECT_GT(e.jitter_degrees(), 0.0);  // a scene without jitter parameters still wobbles when asked
  set_effect(e, "ao", false, "--no-effect");
  EXPECT_FALSE(e.flag(EffectId::ambient_occlusion));
  const InputError unknown = expect_input_error([&] { set_effect(e, "bloom", true, "--effect"); });
  EXPECT_EQ(unknown.file(), "--effect") << unknown.what();
  EXPECT_NE(unknown.rule().find("unknown effect 'bloom'"), std::string::npos) << unknown.what();
  const InputError preset = expect_input_error([&] { apply_preset(e, "glow", "--preset"); });
  EXPECT_EQ(preset.file(), "--preset") << preset.what();
  const InputError parameter =
      expect_input_error([] {
        gpu::SceneEffects record = fallback_effect_record();
        parse_parameter(record, effect_parameter(EffectId::ambient_occlusion, "rays"), "-1", "--ao-rays");
      });
  EXPECT_EQ(parameter.file(), "--ao-rays") << parameter.what();
}

// A rotation by `degrees` about `axis`, then a translation (world).
format::InstanceTransform rigid(dvec3 axis, double degrees, dvec3 translation) {
  format::InstanceTransform t;
  t.linear = glm::mat3_cast(glm::angleAxis(glm::radians(degrees), glm::normalize(axis)));
  t.translation = translation;
  return t;
}

void expect_near(const format::InstanceTransform& a, const format::InstanceTransform& b, double tol) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(a.linear[c][r], b.linear[c][r], tol) << c << "," << r;
  for (int r = 0; r < 3; ++r) EXPECT_NEAR(a.translation[r], b.translation[r], tol * std::max(1.0, glm::length(b.translation)));
}

TEST(Animation, InterpolationIsExactAtKeysAndRigidBetween) {
  const auto a = rigid(dvec3(0, 0, 1), 10, dvec3(1, 2, 3));
  const auto b = rigid(dvec3(0, 0, 1), 100, dvec3(11, 2, -7));
  expect_near(interpolate_transform(a, b, 0), a, 1e-12);
  expect_near(interpolate_transform(a, b, 1), b, 1e-12);
  // Halfway: 55° about z (slerp of rotations about one axis is linear in the angle), midpoint translation.
  expect_near(interpolate_transform(a, b, 0.5), rigid(dvec3(0, 0, 1), 55, dvec3(6, 2, -2)), 1e-12);
  // Scales interpolate per axis.
  format::InstanceTransform big = a;
  big.linear *= 3.0;
  const auto mid = interpolate_transform(a, big, 0.5);
  EXPECT_NEAR(glm::determinant(mid.linear), 8.0, 1e-9);
}

TEST(Animation, KeyframesHoldOutsideTheirRange) {
  const Opened p(format::test::make_sample_scene());
  const auto at = [&](double t) { return animated_instance_transforms(p.package, t); };
  // Instance 1: 90° about z at (50, 0, −5) at t = 0, 180° at (50, 10, −5) at t = 2; instance 0 has no keys.
  expect_near(at(0)[1], rigid(dvec3(0, 0, 1), 90, dvec3(50, 0, -5)), 1e-6);
  expect_near(at(-1)[1], at(0)[1], 0);
  expect_near(at(1)[1], rigid(dvec3(0, 0, 1), 135, dvec3(50, 5, -5)), 1e-6);
  expect_near(at(2)[1], rigid(dvec3(0, 0, 1), 180, dvec3(50, 10, -5)), 1e-6);
  expect_near(at(9)[1], at(2)[1], 0);
  expect_near(at(1)[0], format::InstanceTransform{}, 0);
}

TEST(Animation, SteadyMotionSpinsAboutTheInstanceOriginAndDrifts) {
  format::test::SampleScene s = format::test::make_sample_scene();
  s.keyframes.clear();
  s.effects[0].spin = glm::vec4(0, 1, 0, 30);  // 30°/s about +y
  s.effects[0].velocity = glm::vec4(100, 0, 0, 0);
  const Opened p(s);
  const auto t = animated_instance_transforms(p.package, 2.0);
  // Instance 0 (identity) after 2 s: 60° about y, 200 Å along x; instance 1 keeps its own origin.
  expect_near(t[0], rigid(dvec3(0, 1, 0), 60, dvec3(200, 0, 0)), 1e-12);
  const format::InstanceTransform base = rigid(dvec3(0, 0, 1), 90, dvec3(50, 0, -5));
  format::InstanceTransform expected = base;
  expected.linear = rigid(dvec3(0, 1, 0), 60, dvec3(0)).linear * base.linear;
  expected.translation += dvec3(200, 0, 0);
  expect_near(t[1], expected, 1e-6);
}

TEST(SharedEffects, JitterIsBoundedPerCopyAndPeriodic) {
  const float amplitude = glm::radians(6.0f);
  std::set<std::uint32_t> different;
  for (std::uint32_t copy = 0; copy < 200; ++copy) {
    const glm::uvec2 number(copy * 7919u, copy >> 3);
    const glm::vec4 q = gpu::jitter_rotation(number, 0.7f, amplitude, 0.5f);
    EXPECT_NEAR(glm::length(q), 1.0f, 1e-6f);
    const float angle = 2.0f * std::acos(std::min(1.0f, std::abs(q.w)));
    EXPECT_LE(angle, amplitude + 1e-5f);
    // One period later (f = 0.5 Hz: 2 s) the same rotation.
    const glm::vec4 later = gpu::jitter_rotation(number, 2.7f, amplitude, 0.5f);
    EXPECT_NEAR(std::abs(glm::dot(q, later)), 1.0f, 1e-5f);
    different.insert(std::uint32_t(std::round(angle * 1e5f)));
  }
  EXPECT_GT(different.size(), 150u);  // copies wobble on their own
  // Zero amplitude is the identity; a rotation about the origin keeps |atom| (the mLAS bound).
  EXPECT_EQ(gpu::jitter_rotation(glm::uvec2(5, 0), 1.0f, 0.0f, 1.0f), glm::vec4(0, 0, 0, 1));
  gpu::Affine3 m{glm::mat3(1.0f), glm::vec3(10, 0, 0)};
  const gpu::Affine3 j = gpu::jitter_placement(m, gpu::jitter_rotation(glm::uvec2(3, 1), 0.3f, amplitude, 1.0f));
  const glm::vec3 atom(4, -3, 2);
  EXPECT_NEAR(glm::length(gpu::affine_point(j, atom) - m.translation), glm::length(atom), 1e-5f);
}

TEST(SharedEffects, RayOffsetLeavesTheSurfaceAtAnyScale) {
  for (float scale : {0.001f, 1.0f, 1e3f, 1e6f}) {
    const glm::vec3 n = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
    const glm::vec3 p = glm::vec3(0.7f, -1.3f, 2.1f) * scale;
    const glm::vec3 o = gpu::offset_ray_origin(p, n);
    const float moved = glm::dot(o - p, n);
    EXPECT_GT(moved, 0.0f) << scale;
    // A few hundred ulps at most, never a visible gap.
    EXPECT_LT(glm::length(o - p), 1e-3f * std::max(1.0f, scale)) << scale;
  }
}

TEST(SharedEffects, CosineSamplesStayInTheHemisphere) {
  const glm::vec3 n = glm::normalize(glm::vec3(-0.2f, 0.9f, 0.1f));
  double mean_cos = 0;
  const int count = 4096;
  for (int k = 0; k < count; ++k) {
    const std::uint32_t h = gpu::effect_hash(std::uint32_t(k) * 2u);
    const glm::vec3 d = gpu::cosine_hemisphere(n, gpu::effect_unit(h), gpu::effect_unit(gpu::effect_hash(h + 1u)));
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
    EXPECT_GE(glm::dot(d, n), -1e-6f);
    mean_cos += glm::dot(d, n);
  }
  EXPECT_NEAR(mean_cos / count, 2.0 / 3.0, 0.02);  // E[cos θ] under a cosine-weighted hemisphere
}

}  // namespace
