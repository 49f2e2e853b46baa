// Clash checker vs hand cases and an O(n²) brute force.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "runtime/oracle/clash_check.hpp"
#include "runtime/oracle/explicit_scene.hpp"
#include "tests/oracle/hand_scene.hpp"
#include "tests/oracle/test_package.hpp"

namespace nano::explicit_test {
namespace {

using oracle::ClashAtom;
using oracle::find_clashes;

std::set<std::pair<std::size_t, std::size_t>> brute_force(const std::vector<ClashAtom>& atoms, double factor) {
  std::set<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t a = 0; a < atoms.size(); ++a)
    for (std::size_t b = a + 1; b < atoms.size(); ++b)
      if (atoms[a].copy != atoms[b].copy &&
          glm::distance(atoms[a].position, atoms[b].position) < factor * (atoms[a].radius + atoms[b].radius))
        out.insert({a, b});
  return out;
}

std::set<std::pair<std::size_t, std::size_t>> pairs_of(const oracle::ClashReport& r) {
  std::set<std::pair<std::size_t, std::size_t>> out;
  for (const oracle::Clash& c : r.pairs) out.insert({c.a, c.b});
  return out;
}

TEST(ClashCheck, ThresholdIsSixTenthsOfTheRadiusSum) {
  // r1 + r2 = 3, limit 1.8 Å.
  const std::vector<ClashAtom> atoms = {{1, {0, 0, 0}, 1.0}, {2, {1.79, 0, 0}, 2.0}, {3, {0, 10, 0}, 1.0}, {4, {0, 11.81, 0}, 2.0}};
  const oracle::ClashReport r = find_clashes(atoms);
  ASSERT_EQ(r.count, 1u);
  EXPECT_EQ(r.pairs[0].a, 0u);
  EXPECT_EQ(r.pairs[0].b, 1u);
  EXPECT_NEAR(r.pairs[0].limit, 1.8, 1e-12);
  EXPECT_NEAR(r.pairs[0].distance, 1.79, 1e-12);
}

TEST(ClashCheck, AtomsOfOneCopyNeverClash) {
  const std::vector<ClashAtom> atoms = {{5, {0, 0, 0}, 1.5}, {5, {0.1, 0, 0}, 1.5}, {5, {0, 0.1, 0}, 1.5}};
  EXPECT_EQ(find_clashes(atoms).count, 0u);
}

TEST(ClashCheck, MatchesBruteForceOnDenseCloudsFarFromTheOrigin) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> coord(0, 25), radius(0.5, 2.5);
  for (const glm::dvec3 offset : {glm::dvec3(0), glm::dvec3(-1.5e5, 2e5, -7.25)}) {
    std::vector<ClashAtom> atoms;
    for (int i = 0; i < 1500; ++i)
      atoms.push_back({std::uint64_t(i / 4), offset + glm::dvec3(coord(rng), coord(rng), coord(rng)), radius(rng)});
    const auto want = brute_force(atoms, 0.6);
    const oracle::ClashReport r = find_clashes(atoms, 0.6, atoms.size() * atoms.size());
    EXPECT_EQ(r.count, want.size());
    EXPECT_EQ(pairs_of(r), want);
    EXPECT_GT(want.size(), 100u);  // the cloud is dense enough to test something
    const oracle::ClashReport capped = find_clashes(atoms, 0.6, 10);
    EXPECT_EQ(capped.count, want.size());
    EXPECT_EQ(capped.pairs.size(), 10u);
  }
}

// The checker on oracle output: the hand scene's atoms, counted the same way as by brute force.
TEST(ClashCheck, HandSceneAtomsMatchBruteForce) {
  const TestPackage pkg(hand_scene());
  const oracle::ExplicitScene scene(pkg.package);
  std::vector<ClashAtom> atoms;
  scene.for_each_atom(oracle::WorldBox::everything(),
                      [&](const oracle::AtomSample& a) { atoms.push_back({a.copy->number, a.position, a.radius}); });
  const auto want = brute_force(atoms, 0.6);
  const oracle::ClashReport r = find_clashes(atoms, 0.6, atoms.size());
  EXPECT_EQ(pairs_of(r), want);
}

TEST(ClashCheck, RefusesNonFiniteInput) {
  const std::vector<ClashAtom> atoms = {{1, {0, 0, 0}, 1.0}, {2, {std::nan(""), 0, 0}, 1.0}};
  EXPECT_THROW(find_clashes(atoms), std::invalid_argument);
}

}  // namespace
}  // namespace nano::explicit_test
