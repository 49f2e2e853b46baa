// The per-atom radius judge of `verify` on the hand scene: rays placed against the topmost atom,
// so that nothing else can stand in front of it, at distances from its centre just inside or just
// outside its radius.
#include <gtest/gtest.h>

#include "format/package_view.hpp"
#include "runtime/oracle/atom_radii_judge.hpp"
#include "runtime/oracle/oracle_render.hpp"
#include "tests/oracle/hand_scene.hpp"
#include "tests/oracle/test_package.hpp"

namespace nano::explicit_test {
namespace {

constexpr double kEpsilon = 1e-3;

struct Topmost {
  glm::dvec3 centre{0.0};
  double radius = 0;
  std::uint64_t copy = 0;
  std::uint32_t atom = 0;
};

gpu::PixelHit hit(const Topmost& t, double depth) {
  gpu::PixelHit p = oracle::background_pixel();
  p.depth = float(depth), p.atom = t.atom;
  p.copy_number_lo = std::uint32_t(t.copy), p.copy_number_hi = std::uint32_t(t.copy >> 32);
  return p;
}

class AtomRadiiJudge : public testing::Test {
protected:
  AtomRadiiJudge() : pkg(hand_scene()), scene(pkg.package), bounds(oracle::scene_world_bounds(pkg.package)) {
    scene.for_each_atom(oracle::WorldBox::everything(), [&](const oracle::AtomSample& a) {
      largest = std::max(largest, a.radius);
      if (a.position.z + a.radius > top.centre.z + top.radius || top.radius == 0)
        top = {a.position, a.radius, a.copy->number, a.atom};
    });
  }
  // A ray along +x passing over the topmost atom's centre at height `above` (Å above the centre),
  // starting 20 Å before it; returns the depth of the atom's centre along it in `tc`.
  bool judge(double above, const gpu::PixelHit& test) const {
    const glm::dvec3 eye = top.centre + glm::dvec3(-20, 0, above);
    return oracle::explained_by_atom_radii(scene, bounds, eye, {1, 0, 0}, test, kEpsilon, largest);
  }
  TestPackage pkg;
  oracle::ExplicitScene scene;
  oracle::WorldBox bounds;
  Topmost top;
  double largest = 0;
};

TEST_F(AtomRadiiJudge, GrazingInsideTheRadius) {
  // d = r(1 − ε/2): exact radii hit, shrunk ones miss: either outcome is explained, at the right depth.
  const double d = top.radius * (1 - kEpsilon / 2);
  const double entry = 20 - std::sqrt(top.radius * top.radius - d * d);
  EXPECT_TRUE(judge(d, oracle::background_pixel()));
  EXPECT_TRUE(judge(d, hit(top, entry)));
  EXPECT_TRUE(judge(d, hit(top, 20)));  // the tangent point, where a shrunk atom would stop being hit
  EXPECT_FALSE(judge(d, hit(top, entry - 0.5)));
  EXPECT_FALSE(judge(d, hit(top, 20.5)));
}

TEST_F(AtomRadiiJudge, GrazingOutsideTheRadius) {
  // d = r(1 + ε/2): exact radii miss, grown ones hit.
  const double d = top.radius * (1 + kEpsilon / 2);
  EXPECT_TRUE(judge(d, oracle::background_pixel()));
  EXPECT_TRUE(judge(d, hit(top, 20)));
  EXPECT_FALSE(judge(d, hit(top, 19)));
  // Beyond the grown radius nothing can be claimed.
  EXPECT_FALSE(judge(top.radius * (1 + 3 * kEpsilon), hit(top, 20)));
}

TEST_F(AtomRadiiJudge, ClearHitsAreNotExplainedAway) {
  // Straight down through the topmost atom's centre: it blocks the ray whatever the radii, and
  // nothing stands above it. Background and any other atom are real differences.
  const glm::dvec3 eye = top.centre + glm::dvec3(0, 0, 30);
  const auto judge_down = [&](const gpu::PixelHit& test) {
    return oracle::explained_by_atom_radii(scene, bounds, eye, {0, 0, -1}, test, kEpsilon, largest);
  };
  EXPECT_TRUE(judge_down(hit(top, 30 - top.radius)));
  EXPECT_FALSE(judge_down(hit(top, 30 - top.radius + 0.01)));
  EXPECT_FALSE(judge_down(oracle::background_pixel()));
  Topmost other = top;
  other.atom += 1;
  EXPECT_FALSE(judge_down(hit(other, 30 - top.radius)));
  other = top;
  other.copy += 1;
  EXPECT_FALSE(judge_down(hit(other, 30 - top.radius)));
}

TEST_F(AtomRadiiJudge, ClippedAtomsExplainNothing) {
  // Grazing the topmost atom explains a hit on it — unless a clip plane removes its centre, then a
  // hit on it is a clipping error however the radii change.
  const double d = top.radius * (1 - kEpsilon / 2);
  const glm::dvec3 eye = top.centre + glm::dvec3(-20, 0, d);
  const glm::dvec4 removes_top(0, 0, -1, top.centre.z - 0.5);  // keeps z ≤ centre − 0.5
  const std::vector<glm::dvec4> clip{removes_top};
  EXPECT_TRUE(oracle::explained_by_atom_radii(scene, bounds, eye, {1, 0, 0}, hit(top, 20), kEpsilon, largest));
  EXPECT_FALSE(oracle::explained_by_atom_radii(scene, bounds, eye, {1, 0, 0}, hit(top, 20), kEpsilon, largest, clip));
}

TEST_F(AtomRadiiJudge, EyeInsideAnAtomIsNeverExplained) {
  const glm::dvec3 eye = top.centre;
  EXPECT_FALSE(oracle::explained_by_atom_radii(scene, bounds, eye, {1, 0, 0}, hit(top, 1.0), kEpsilon, largest));
  EXPECT_FALSE(oracle::explained_by_atom_radii(scene, bounds, eye, {1, 0, 0}, oracle::background_pixel(), kEpsilon, largest));
}

// Two atoms of a copy whose spheres overlap, and a ray entering both at one point of the circle where
// their surfaces meet: a tie, whichever of the two is named. Apart by more than the tolerance, or a
// third atom named, it is not.
TEST_F(AtomRadiiJudge, TwoSurfacesMeetingTheRayAtOnePointAreATie) {
  Topmost other;
  double nearest = INFINITY;
  scene.for_each_atom(oracle::WorldBox::everything(), [&](const oracle::AtomSample& a) {
    const double d = glm::length(a.position - top.centre);
    if (a.copy->number == top.copy && a.atom != top.atom && d < a.radius + top.radius && d > 0.1 && d < nearest)
      nearest = d, other = {a.position, a.radius, a.copy->number, a.atom};
  });
  ASSERT_TRUE(std::isfinite(nearest)) << "the hand scene's topmost atom overlaps none of its copy";
  const glm::dvec3 u = (other.centre - top.centre) / nearest;
  const double along = (nearest * nearest + top.radius * top.radius - other.radius * other.radius) / (2 * nearest);
  const double ring = std::sqrt(top.radius * top.radius - along * along);
  const glm::dvec3 v = glm::normalize(glm::cross(u, std::abs(u.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
  const glm::dvec3 meet = top.centre + along * u + ring * v;
  const glm::dvec3 dir = -glm::normalize((meet - top.centre) / top.radius + (meet - other.centre) / other.radius);
  const glm::dvec3 eye = meet - 5.0 * dir;
  EXPECT_TRUE(oracle::explained_as_tie(scene, eye, dir, hit(other, 5.0), hit(top, 5.0), largest));
  EXPECT_TRUE(oracle::explained_as_tie(scene, eye, dir, hit(top, 5.0), hit(other, 5.0), largest));
  EXPECT_FALSE(oracle::explained_as_tie(scene, eye, dir, hit(other, 5.01), hit(top, 5.0), largest));
  Topmost third = other;
  third.atom = other.atom + 1 == top.atom ? other.atom + 2 : other.atom + 1;
  EXPECT_FALSE(oracle::explained_as_tie(scene, eye, dir, hit(third, 5.0), hit(top, 5.0), largest));
  EXPECT_FALSE(oracle::explained_as_tie(scene, eye, dir, oracle::background_pixel(), hit(top, 5.0), largest));
}

TEST_F(AtomRadiiJudge, AnEyeInsideAnAtomMeetsItWhereTheRayLeavesIt) {
  // From the topmost atom's centre along +z nothing stands above it: the ray leaves it at its radius.
  const glm::dvec3 eye = top.centre;
  EXPECT_TRUE(oracle::explained_as_tie(scene, eye, {0, 0, 1}, hit(top, top.radius), hit(top, top.radius), largest));
  EXPECT_FALSE(oracle::explained_as_tie(scene, eye, {0, 0, 1}, hit(top, top.radius - 0.01), hit(top, top.radius), largest));
}

// A copy placed a few float steps off: straight down onto the topmost atom its entry moves by the
// shift; met obliquely, by more; beyond what a shift of `slack` gives, nothing is explained.
TEST_F(AtomRadiiJudge, ACentreShiftedByTheSlackExplainsTheDepthsItGives) {
  constexpr double kSlack = 0.016;
  const glm::dvec3 down_eye = top.centre + glm::dvec3(0, 0, 30);
  const auto down = [&](double depth) {
    return oracle::explained_by_placement(scene, down_eye, {0, 0, -1}, hit(top, depth), kSlack, largest);
  };
  const double entry = 30 - top.radius;
  EXPECT_TRUE(down(entry));
  EXPECT_TRUE(down(entry + 0.9 * kSlack));
  EXPECT_TRUE(down(entry - 0.9 * kSlack));
  EXPECT_FALSE(down(entry + 3 * kSlack));
  EXPECT_FALSE(down(entry - 3 * kSlack));
  // 0.9 r off the centre the ray meets the sphere obliquely: a sideways shift of the slack moves the
  // entry by several times the slack, the most the rule grants.
  const double d = 0.9 * top.radius;
  const glm::dvec3 side_eye = top.centre + glm::dvec3(-20, 0, d);
  const auto side = [&](double depth) {
    return oracle::explained_by_placement(scene, side_eye, {1, 0, 0}, hit(top, depth), kSlack, largest);
  };
  const double oblique = 20 - std::sqrt(top.radius * top.radius - d * d);
  const double shifted = 20 - std::sqrt(top.radius * top.radius - (d + kSlack) * (d + kSlack));
  EXPECT_GT(shifted - oblique, 2 * kSlack);
  EXPECT_TRUE(side(shifted));
  EXPECT_FALSE(side(shifted + 3 * kSlack));
  Topmost other = top;
  other.atom += 1;
  EXPECT_FALSE(oracle::explained_by_placement(scene, down_eye, {0, 0, -1}, hit(other, entry), kSlack, largest));
  EXPECT_FALSE(oracle::explained_by_placement(scene, top.centre, {0, 0, -1}, hit(top, top.radius), kSlack, largest));
}

// The device places the medium relative to the eye's box in float, so 10^5 Å from the eye a medium
// atom may stand a few float steps (0.0078 Å each) apart: medium_ulps widens it by that many.
TEST(AtomRadiiJudgeMedium, FarMediumAtomsMayStandTheirFloatStepsApart) {
  const TestPackage pkg{format::test::medium_only_sample_scene()};
  const oracle::ExplicitScene scene(pkg.package);
  const oracle::WorldBox bounds = oracle::scene_world_bounds(pkg.package, &scene);
  Topmost top;
  double largest = 0;
  scene.for_each_atom(oracle::WorldBox::everything(), [&](const oracle::AtomSample& a) {
    ASSERT_EQ(a.copy->id.kind, placement::CopyKind::medium);
    largest = std::max(largest, a.radius);
    if (a.position.z + a.radius > top.centre.z + top.radius || top.radius == 0) top = {a.position, a.radius, a.copy->number, a.atom};
  });
  ASSERT_GT(top.radius, 0);
  constexpr double kFar = 1e5, kUlps = 4;
  const double step = double(std::nextafter(float(kFar), INFINITY) - float(kFar));
  const auto judge = [&](double above, double ulps) {
    const glm::dvec3 eye = top.centre + glm::dvec3(-kFar, 0, above);
    return oracle::explained_by_atom_radii(scene, bounds, eye, {1, 0, 0}, hit(top, kFar), kEpsilon, largest, {}, ulps);
  };
  const double just_beyond_radii = top.radius * (1 + kEpsilon) + kUlps * step / 2;
  EXPECT_FALSE(judge(just_beyond_radii, 0));
  EXPECT_TRUE(judge(just_beyond_radii, kUlps));
  EXPECT_FALSE(judge(top.radius * (1 + kEpsilon) + 2 * kUlps * step, kUlps));  // beyond the steps too
}

}  // namespace
}  // namespace nano::explicit_test

namespace nano::explicit_test {
namespace {

// verify traces again only the pixels it disagrees on (OracleRenderOptions::only_pixels): each gets
// the hit the whole image gives it, compartment and medium alike, and every other pixel stays empty.
void expect_pixels_as_in_the_whole_image(const TestPackage& pkg, const glm::vec3& eye, const glm::vec3& centre) {
  const oracle::ExplicitScene scene(pkg.package);
  const gpu::Camera camera = gpu::camera_look_at(eye, centre, {0, 1, 0}, 60.f, 48, 32);
  const std::vector<gpu::PixelHit> whole = oracle::oracle_render(scene, pkg.package, camera);
  oracle::OracleRenderOptions some;
  for (std::uint32_t p = 0; p < whole.size(); p += 7) some.only_pixels.push_back(p);
  const std::vector<gpu::PixelHit> part = oracle::oracle_render(scene, pkg.package, camera, some);
  ASSERT_EQ(part.size(), whole.size());
  std::size_t hits = 0;
  for (std::uint32_t p = 0; p < whole.size(); ++p) {
    const bool traced = p % 7 == 0;
    const gpu::PixelHit& expected = traced ? whole[p] : oracle::background_pixel();
    EXPECT_EQ(oracle::classify(expected, part[p]), oracle::PixelDifference::none) << "pixel " << p;
    EXPECT_EQ(part[p].depth, expected.depth) << "pixel " << p;
    hits += traced && whole[p].atom != gpu::kNoHit;
  }
  std::size_t whole_hits = 0;
  for (const gpu::PixelHit& h : whole) whole_hits += h.atom != gpu::kNoHit;
  EXPECT_GT(hits, 5u) << "the view must show atoms at some of the traced pixels (" << whole_hits << " of " << whole.size() << " in all)";
  some.only_pixels = {std::uint32_t(whole.size())};
  EXPECT_THROW(oracle::oracle_render(scene, pkg.package, camera, some), InputError);
}

TEST(OracleRenderPixels, TracedPixelsHitWhatTheWholeImageHits) {
  const TestPackage pkg{hand_scene()};
  const glm::vec3 square_centre(kL / 2, kL / 2, 0);  // the first flat membrane instance's
  expect_pixels_as_in_the_whole_image(pkg, square_centre + glm::vec3(1, 0.5, 25), square_centre);
}

TEST(OracleRenderPixels, TracedPixelsHitTheMediumAsTheWholeImageDoes) {
  const TestPackage pkg{format::test::medium_only_sample_scene()};
  const gpu::Medium& medium = format::PackageView(pkg.package).medium[0];
  const glm::vec3 lo(medium.region_min), hi(medium.region_max);
  expect_pixels_as_in_the_whole_image(pkg, hi + 0.3f * (hi - lo), 0.5f * (lo + hi));
}

}  // namespace
}  // namespace nano::explicit_test
