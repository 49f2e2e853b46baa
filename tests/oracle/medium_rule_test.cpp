// The medium's keep rule on the CPU (runtime/placement/medium_rule.hpp) on the format tests' sample
// package, whose one exclusion field holds |p| − 1 (clamped to ±3, margin 0.5) around the
// compartment origin: hand-computed values, instance frames and the oracle's enumeration of a box.
#include "runtime/placement/medium_rule.hpp"

#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "format/package.hpp"
#include "runtime/placement/copy_enumerator.hpp"
#include "tests/format/sample_scene.hpp"

namespace nano::placement {
namespace {

format::Package sample_package() { return format::Package::from_bytes(format::test::build(format::test::make_sample_scene())); }

std::vector<format::InstanceTransform> transforms_of(const format::PackageView& p) {
  std::vector<format::InstanceTransform> t;
  for (const gpu::CompartmentInstance& ci : p.compartment_instances) t.push_back(format::instance_transform(ci));
  return t;
}

TEST(MediumRule, InstanceRecordsMapRegionSpaceToCompartmentSpace) {
  const format::Package package = sample_package();
  const format::PackageView p(package);
  const auto records = medium_instances(p, transforms_of(p));
  ASSERT_EQ(records.size(), 2u);
  // Instance 1: world = (50 − y, x, z − 5); the region starts at (−20, −20, −20).
  const glm::dvec3 world(47, 4, -3), region = world - glm::dvec3(-20);
  const glm::vec3 local = gpu::medium_to_compartment(records[1], glm::vec3(region));
  EXPECT_NEAR(local.x, 4, 1e-4);   // x = world y
  EXPECT_NEAR(local.y, 3, 1e-4);   // y = 50 − world x
  EXPECT_NEAR(local.z, 2, 1e-4);   // z = world z + 5
  EXPECT_FLOAT_EQ(records[1].stretch.x, 1.0f);  // rigid
  EXPECT_EQ(records[1].ids.x, 0u);
}

TEST(MediumRule, AScaledInstanceStretchesItsClearance) {
  const format::Package package = sample_package();
  const format::PackageView p(package);
  std::vector<format::InstanceTransform> t = transforms_of(p);
  t[0].linear = glm::dmat3(2.0, 0, 0, 0, 3.0, 0, 0, 0, 0.5);
  EXPECT_NEAR(medium_instances(p, t)[0].stretch.x, 0.5f, 1e-6);  // the least singular value
}

TEST(MediumRule, TheExclusionBoxHoldsTheFieldGrid) {
  const format::Package package = sample_package();
  const format::PackageView p(package);
  const format::InstanceTransform t = transforms_of(p)[1];
  const auto [lo, hi] = exclusion_box(p.exclusion_fields[0], t, glm::dvec3(-20));
  // Grid corners (−2..2)³ under world = (50 − y, x, z − 5), less the region minimum, grown by 1 Å.
  EXPECT_NEAR(lo.x, 48 + 20 - 1, 1e-9);
  EXPECT_NEAR(hi.x, 52 + 20 + 1, 1e-9);
  EXPECT_NEAR(lo.z, -7 + 20 - 1, 1e-9);
}

TEST(MediumRule, ValuesAndDecisionsFollowTheField) {
  const format::Package package = sample_package();
  const format::PackageView p(package);
  const auto records = medium_instances(p, transforms_of(p));
  // Instance 0 is the identity: the compartment origin is region point (20, 20, 20).
  EXPECT_NEAR(exclusion_value(p, records[0], glm::vec3(20)), -1.0f, 1e-6);
  EXPECT_NEAR(exclusion_value(p, records[0], glm::vec3(21, 20, 20)), 0.0f, 1e-6);
  EXPECT_NEAR(exclusion_value(p, records[0], glm::vec3(20, 21.5f, 20)), 0.5f, 1e-6);  // halfway between 0 and 1
  EXPECT_EQ(exclusion_value(p, records[0], glm::vec3(40)), 3.0f);                     // beyond the grid: its clamp
  const std::vector<std::uint32_t> near{0};
  // Clear iff value − 0.5 ≥ r + clearance (1 Å): at 2 Å from the origin the value is 1.
  EXPECT_FALSE(medium_copy_kept(p, records, near, glm::vec3(22, 20, 20), 0.1f));
  EXPECT_TRUE(medium_copy_kept(p, records, near, glm::vec3(40), 1.0f));
  EXPECT_TRUE(medium_copy_kept(p, records, {}, glm::vec3(20), 1.0f));  // no instance near: nothing to keep clear of
}

// for_each_medium_copy of a world box gives exactly the kept copies of the boxes it covers, each
// once, numbered after every instance's copies.
TEST(MediumRule, TheEnumeratorKeepsWhatTheRuleKeeps) {
  const format::Package package = format::Package::from_bytes(format::test::build(format::test::medium_only_sample_scene()));
  const format::PackageView p(package);
  const CopyEnumerator copies(package);
  ASSERT_TRUE(copies.has_medium());
  const auto records = medium_instances(p, transforms_of(p));
  std::set<std::uint64_t> numbers;
  std::size_t kept = 0;
  copies.for_each_medium_copy(WorldBox::everything(), [&](const Copy& c) {
    EXPECT_EQ(c.id.kind, CopyKind::medium);
    EXPECT_EQ(c.id.compartment_instance, gpu::NANO_MEDIUM_OWNER);
    EXPECT_TRUE(numbers.insert(c.number).second);
    ++kept;
  });
  // By hand: the region's 512 boxes hold one copy each (the one cube), at (2, 2, 2) in its box.
  std::size_t expected = 0;
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        const glm::vec3 c = gpu::medium_copy_centre(glm::ivec3(i, j, k), 5.0f, glm::vec3(2, 2, 2));
        std::vector<std::uint32_t> near;
        for (std::uint32_t n = 0; n < records.size(); ++n) {
          const auto [lo, hi] = exclusion_box(p.exclusion_fields[0], transforms_of(p)[n], glm::dvec3(-20));
          if (glm::all(glm::greaterThanEqual(glm::dvec3(c), lo)) && glm::all(glm::lessThanEqual(glm::dvec3(c), hi))) near.push_back(n);
        }
        expected += medium_copy_kept(p, records, near, c, p.molecules[0].aabb_min.w);
      }
  EXPECT_EQ(kept, expected);
  EXPECT_LT(kept, 512u);  // the copies at the identity instance's origin are refused
  EXPECT_GE(*numbers.begin(), copies.copy_number_limit() - 512u);
  EXPECT_LT(*numbers.rbegin(), copies.copy_number_limit());
  CopyOptions hidden;
  hidden.medium = false;
  EXPECT_FALSE(CopyEnumerator(package, hidden).has_medium());
  // Its molecule type hidden, the medium is there and keeps nothing.
  CopyOptions no_type;
  no_type.visibility.hidden_molecule_types = {1, 1};
  std::size_t left = 0;
  CopyEnumerator(package, no_type).for_each_medium_copy(WorldBox::everything(), [&](const Copy&) { ++left; });
  EXPECT_EQ(left, 0u);
}

}  // namespace
}  // namespace nano::placement
