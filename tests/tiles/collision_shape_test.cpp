#include "bake/tiles/collision_shape.hpp"
#include "bake/tiles/copy_neighbourhood.hpp"
#include "bake/tiles/rotation_sampling.hpp"
#include "common/error.hpp"
#include "tests/tiles/tiles_test_support.hpp"

#include <gtest/gtest.h>

namespace nano::tiles {
namespace {

// Brute force over all atom pairs, with the test's own rotation.
bool brute_force_collide(const MoleculeType& a, const Instance& ia, const MoleculeType& b, const Instance& ib, float f) {
  for (const AtomSphere& x : a.atoms)
    for (const AtomSphere& y : b.atoms) {
      const glm::vec3 px = ia.position + test::rotate(ia.rotation, x.centre);
      const glm::vec3 py = ib.position + test::rotate(ib.rotation, y.centre);
      if (glm::length(px - py) < f * (x.radius + y.radius)) return true;
    }
  return false;
}

Pose pose(const Instance& in) { return {in.position, glm::mat3_cast(in.rotation)}; }

// Rigid means nothing for the tiles to survive; the facets' sag alone bounds a tilt and is no
// distortion by itself.
TEST(SurfaceDistortion, RigidOnlyWithoutStretchCurvatureOrTilt) {
  EXPECT_TRUE(SurfaceDistortion{}.rigid());
  EXPECT_TRUE((SurfaceDistortion{0.f, 0.f, 0.f, 3.f}).rigid());
  EXPECT_FALSE((SurfaceDistortion{0.03f, 0.f, 0.f, 0.f}).rigid());
  EXPECT_FALSE((SurfaceDistortion{0.f, 1e-3f, 0.f, 0.f}).rigid());
  EXPECT_FALSE((SurfaceDistortion{0.f, 0.f, 0.007f, 0.f}).rigid());
}

TEST(CollisionShape, RadiiMatchTheAtoms) {
  const MoleculeType lipid = test::make_lipid();
  const CollisionShape s(lipid);
  float r = 0.f, rz = 0.f;
  for (const AtomSphere& a : lipid.atoms) {
    r = std::max(r, glm::length(a.centre) + a.radius);
    rz = std::max(rz, glm::length(glm::vec2(a.centre)) + a.radius);
  }
  EXPECT_FLOAT_EQ(s.radius(), r);
  EXPECT_NEAR(s.radius_about_axis({0, 0, 2}), rz, 1e-5f);
  EXPECT_FLOAT_EQ(s.max_atom_radius(), 1.7f);
  EXPECT_EQ(s.atoms().size(), lipid.atoms.size());
}

TEST(CollisionShape, TouchesAgreesWithBruteForce) {
  const MoleculeType blob = test::make_protein();
  const CollisionShape s(blob);
  test::TestRng rng{5};
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    const glm::vec3 p(60 * rng.next() - 30, 60 * rng.next() - 30, 60 * rng.next() - 30);
    const float r = 0.5f + 2.f * float(rng.next());
    bool expect = false;
    for (const AtomSphere& a : blob.atoms) expect |= glm::length(p - a.centre) < 0.8f * (r + a.radius);
    ASSERT_EQ(s.touches(p, r, 0.8f), expect) << i;
    hits += expect;
  }
  EXPECT_GT(hits, 300);
  EXPECT_LT(hits, 2700);
}

TEST(CollisionShape, CopiesCollideAgreesWithBruteForce) {
  const MoleculeType a = test::make_protein(), b = test::make_lipid();
  const CollisionShape sa(a), sb(b);
  SplitMix64 rng(77);
  int hits = 0;
  for (int i = 0; i < 400; ++i) {
    const Instance ia{0, {0, 0, 0}, uniform_rotation(rng)};
    const Instance ib{1, {float(rng.uniform(-45, 45)), float(rng.uniform(-45, 45)), float(rng.uniform(-45, 45))},
                      uniform_rotation(rng)};
    const bool expect = brute_force_collide(a, ia, b, ib, 1.f);
    ASSERT_EQ(copies_collide(sa, pose(ia), sb, pose(ib), ClashRule{1.f}), expect) << i;
    ASSERT_EQ(copies_collide(sb, pose(ib), sa, pose(ia), ClashRule{1.f}), expect) << i;
    hits += expect;
  }
  EXPECT_GT(hits, 40);
  EXPECT_LT(hits, 360);
}

// The chart's in-plane map at a copy: a symmetric stretch with eigenvalues in [1, 1 + e] along a
// random direction, applied to tile-space x, y of the centre only (atoms stay rigid).
Instance stretched(const Instance& in, float angle, float major, float minor) {
  const glm::vec2 u(std::cos(angle), std::sin(angle)), v(-u.y, u.x);
  const glm::vec2 p(in.position);
  const glm::vec2 q = major * glm::dot(p, u) * u + minor * glm::dot(p, v) * v;
  return {in.type, {q.x, q.y, in.position.z}, in.rotation};
}

TEST(CollisionShape, StretchRuleCoversEveryStretchInItsRange) {
  const MoleculeType a = test::make_lipid(), b = test::make_lipid();
  const CollisionShape sa(a), sb(b);
  SplitMix64 rng(19);
  constexpr float e = 0.4f;
  int cleared = 0, caught = 0, flagged = 0;
  for (int i = 0; i < 600; ++i) {
    const Instance ia{0, {float(rng.uniform(-20, 20)), float(rng.uniform(-20, 20)), float(rng.uniform(-12, 12))},
                      uniform_rotation(rng)};
    const Instance ib{1, {float(rng.uniform(-20, 20)), float(rng.uniform(-20, 20)), float(rng.uniform(-12, 12))},
                      uniform_rotation(rng)};
    const bool rule = copies_collide(sa, pose(ia), sb, pose(ib), ClashRule{1.f, {e, 0.f, 0.f}});
    ASSERT_EQ(rule, copies_collide(sb, pose(ib), sa, pose(ia), ClashRule{1.f, {e, 0.f, 0.f}})) << i;
    const bool rigid = brute_force_collide(a, ia, b, ib, 1.f);
    if (rigid) {  // the identity is one of the stretches
      ASSERT_TRUE(rule) << i;
    }
    // Extremes and interior points of the eigenvalue range; pairs only the rule rejects get a
    // finer search for the stretch that makes them clash.
    const int samples = rule && !rigid ? 2000 : 24;
    bool some_stretch_clashes = false;
    for (int k = 0; k < samples && !some_stretch_clashes; ++k) {
      const float angle = float(rng.uniform(0, 6.2832));
      const float major = k % 3 == 0 ? 1.f + e : 1.f + e * float(rng.uniform(0, 1));
      const float minor = k % 6 == 0 ? 1.f : 1.f + (major - 1.f) * float(rng.uniform(0, 1));
      const bool clash = brute_force_collide(a, stretched(ia, angle, major, minor), b, stretched(ib, angle, major, minor), 1.f);
      if (!rule) {
        ASSERT_FALSE(clash) << "pair " << i << " clashes under a stretch the rule cleared";
      }
      some_stretch_clashes |= clash;
    }
    flagged += rule && !rigid;
    cleared += !rule;
    caught += rule && !rigid && some_stretch_clashes;
  }
  // Both outcomes occur, and the rule rejects pairs that really do clash once stretched (the bound
  // is exact per atom pair; the random search finds the clashing stretch for a good part of them).
  EXPECT_GT(cleared, 60);
  EXPECT_GT(flagged, 10);
  EXPECT_GT(caught, flagged / 4) << "rejected only by the rule: " << flagged;
}

TEST(CollisionShape, RejectsEmptyOrBadAtoms) {
  EXPECT_THROW(CollisionShape(MoleculeType{"empty", {}, 0.f, {0, 0, 1}}), InputError);
  EXPECT_THROW(CollisionShape(MoleculeType{"zero", {{{0, 0, 0}, 0.f}}, 0.f, {0, 0, 1}}), InputError);
  EXPECT_THROW(CollisionShape(MoleculeType{"nan", {{{NAN, 0, 0}, 1.f}}, 0.f, {0, 0, 1}}), InputError);
}

// Every third placed copy is retired again: the neighbourhood then finds exactly the collisions with
// the copies still standing.
TEST(CopyNeighbourhood, FindsExactlyTheCollidingPlacedCopies) {
  const std::vector<MoleculeType> types{test::make_protein(), test::make_lipid()};
  const std::vector<CollisionShape> shapes{CollisionShape(types[0]), CollisionShape(types[1])};
  CopyNeighbourhood hood(shapes, 40.f);
  std::vector<Instance> placed, standing;
  SplitMix64 rng(8);
  for (int i = 0; i < 30; ++i) {
    const Instance in{uint32_t(i % 2), {float(rng.uniform(-150, 150)), float(rng.uniform(-150, 150)), float(rng.uniform(-20, 20))},
                      uniform_rotation(rng)};
    placed.push_back(in);
    EXPECT_EQ(hood.add(in.type, pose(in)), std::size_t(i));
  }
  EXPECT_EQ(hood.size(), 30u);
  CopyNeighbourhood thinned = hood;
  for (std::size_t i = 0; i < placed.size(); ++i)
    if (i % 3 == 0) thinned.retire(i);
    else standing.push_back(placed[i]);
  int hits = 0, hits_thinned = 0;
  for (int i = 0; i < 120; ++i) {
    const Instance c{uint32_t(i % 2), {float(rng.uniform(-150, 150)), float(rng.uniform(-150, 150)), float(rng.uniform(-20, 20))},
                     uniform_rotation(rng)};
    bool expect = false, expect_thinned = false;
    for (const Instance& p : placed) expect = expect || brute_force_collide(types[c.type], c, types[p.type], p, 0.9f);
    for (const Instance& p : standing) expect_thinned = expect_thinned || brute_force_collide(types[c.type], c, types[p.type], p, 0.9f);
    ASSERT_EQ(hood.collides(c.type, pose(c), ClashRule{0.9f}), expect) << i;
    ASSERT_EQ(thinned.collides(c.type, pose(c), ClashRule{0.9f}), expect_thinned) << i;
    hits += expect;
    hits_thinned += expect_thinned;
  }
  EXPECT_GT(hits_thinned, 3);
  EXPECT_LT(hits_thinned, hits) << "retiring copies must free some room";
}

}  // namespace
}  // namespace nano::tiles
