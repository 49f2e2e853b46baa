// The pixel comparison of `verify`: classification and what a radius change of ±ε explains.
#include <cmath>

#include <gtest/gtest.h>

#include "runtime/oracle/oracle_render.hpp"
#include "runtime/oracle/render_compare.hpp"

namespace nano::oracle {
namespace {

gpu::PixelHit hit(std::uint32_t atom, std::uint32_t copy, float depth) {
  gpu::PixelHit p = background_pixel();
  p.depth = depth, p.atom = atom, p.copy_number_lo = copy, p.copy_number_hi = 0;
  p.compartment_instance = 0, p.element = 1, p.kind = 0, p.cell = glm::ivec4(0), p.instance = copy;
  return p;
}

TEST(RenderCompare, ClassifiesByAtomIdsAndDepthTolerance) {
  const gpu::PixelHit a = hit(5, 9, 100.0f);
  EXPECT_EQ(classify(a, a), PixelDifference::none);
  EXPECT_EQ(classify(a, hit(5, 9, 100.0009f)), PixelDifference::none);  // within 1e-3 Å
  EXPECT_EQ(classify(a, hit(5, 9, 100.01f)), PixelDifference::depth_only);
  EXPECT_EQ(classify(a, hit(6, 9, 100.0f)), PixelDifference::different_atom);
  EXPECT_EQ(classify(a, background_pixel()), PixelDifference::missed);
  gpu::PixelHit other_ids = a;
  other_ids.element = 2;
  EXPECT_EQ(classify(a, other_ids), PixelDifference::different_ids);
  gpu::PixelHit nan = a;
  nan.depth = NAN;
  EXPECT_EQ(classify(a, nan), PixelDifference::bad_depth);
  EXPECT_EQ(classify(background_pixel(), background_pixel()), PixelDifference::none);
  EXPECT_DOUBLE_EQ(depth_tolerance(10), 1e-3);
  EXPECT_DOUBLE_EQ(depth_tolerance(1e4), 0.1);
}

TEST(RenderCompare, RadiusChangeExplainsGrazingTouchesOnly) {
  const gpu::PixelHit ref = hit(5, 9, 100.0f);
  // A grazing miss: the device sees the atom behind, which the shrunk world shows as well.
  EXPECT_TRUE(explained_by_radius_change(hit(7, 9, 101.0f), ref, hit(7, 9, 101.0f), ref, 0.1));
  // A touch the device finds that the oracle misses, which the grown world finds.
  EXPECT_TRUE(explained_by_radius_change(ref, hit(7, 9, 101.0f), hit(7, 9, 101.0f), ref, 0.1));
  // A depth between the perturbed worlds' depths on the same atom.
  EXPECT_TRUE(explained_by_radius_change(hit(5, 9, 100.02f), ref, hit(5, 9, 100.03f), hit(5, 9, 99.99f), 0.1));
  // Shrinking loses the atom: the depth is only known to within the grazing slack.
  EXPECT_TRUE(explained_by_radius_change(hit(5, 9, 100.05f), ref, hit(7, 9, 101.0f), hit(5, 9, 99.99f), 0.1));
  EXPECT_FALSE(explained_by_radius_change(hit(5, 9, 100.5f), ref, hit(7, 9, 101.0f), hit(5, 9, 99.99f), 0.1));
  // A different atom that no perturbed world shows is a real difference.
  EXPECT_FALSE(explained_by_radius_change(hit(8, 3, 90.0f), ref, ref, ref, 0.1));
  // A depth off on a well-conditioned hit (both perturbed worlds agree closely) is real.
  EXPECT_FALSE(explained_by_radius_change(hit(5, 9, 100.2f), ref, hit(5, 9, 100.001f), hit(5, 9, 99.999f), 0.1));
}

}  // namespace
}  // namespace nano::oracle
