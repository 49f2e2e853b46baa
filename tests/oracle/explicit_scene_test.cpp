// The explicit-instancing oracle against plane geometry (hand_scene.hpp) and against a brute-force
// filter over every atom of every copy.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <stdexcept>
#include <string>

#include "common/error.hpp"
#include "format/validator.hpp"
#include "runtime/oracle/explicit_scene.hpp"
#include "tests/oracle/hand_scene.hpp"
#include "tests/oracle/test_package.hpp"

namespace nano::explicit_test {
namespace {

using oracle::AtomSample;
using oracle::Copy;
using oracle::CopyKind;
using oracle::ExplicitScene;
using oracle::WorldBox;

struct Found {
  AtomKey key;
  std::uint64_t number;
  std::uint32_t element;  // triangle or box
  glm::dvec3 position;
  double radius;
};

std::vector<Found> atoms_in(const ExplicitScene& scene, const WorldBox& box) {
  std::vector<Found> out;
  scene.for_each_atom(box, [&](const AtomSample& a) {
    const oracle::CopyId& id = a.copy->id;
    out.push_back({{id.compartment_instance, int(id.kind), id.cell, id.instance, a.atom}, a.copy->number, id.element,
                   a.position, a.radius});
  });
  return out;
}

// Every expected atom of compartment instance `ci` found once at its hand-computed place, and
// nothing else found for that instance.
void expect_instance_matches(std::uint32_t ci) {
  const SampleScene s = hand_scene();
  const TestPackage pkg(s);
  const ExplicitScene scene(pkg.package);
  Expected expected;
  for (const auto& [key, atom] : expected_atoms(s))
    if (key.compartment_instance == ci) expected.emplace(key, atom);
  ASSERT_GT(expected.size(), 10u);
  std::set<AtomKey> seen;
  for (const Found& f : atoms_in(scene, WorldBox::everything())) {
    if (f.key.compartment_instance != ci) continue;
    SCOPED_TRACE("cell " + std::to_string(f.key.cell.x) + "," + std::to_string(f.key.cell.y) + "," +
                 std::to_string(f.key.cell.z) + " instance " + std::to_string(f.key.instance) + " atom " +
                 std::to_string(f.key.atom));
    EXPECT_TRUE(seen.insert(f.key).second) << "atom produced twice";
    const auto it = expected.find(f.key);
    ASSERT_NE(it, expected.end()) << "atom of a copy the hand oracle does not have";
    EXPECT_LE(glm::distance(f.position, it->second.position), 1e-3);
    EXPECT_NEAR(f.radius, it->second.radius, 1e-6);
  }
  EXPECT_EQ(seen.size(), expected.size()) << "copies missing";
}

TEST(ExplicitScene, FlatSquareMembraneMatchesPlaneGeometry) { expect_instance_matches(0); }
TEST(ExplicitScene, MirroredChartMatchesPlaneGeometry) { expect_instance_matches(1); }
TEST(ExplicitScene, RotatedTranslatedInstanceMatchesPlaneGeometry) { expect_instance_matches(2); }
TEST(ExplicitScene, CoreGridInsideOutsideBoundaryAndWrappingRecipe) { expect_instance_matches(3); }

// Molecule 1 of square 0 sits at tile (20, 20): in cells (a, a) its UV lies exactly on the
// diagonal both triangles share. Each such copy must come from exactly one of the two triangles.
TEST(ExplicitScene, MoleculesOnSharedEdgeExportedOnce) {
  const SampleScene s = hand_scene();
  const TestPackage pkg(s);
  const ExplicitScene scene(pkg.package);
  for (std::uint32_t ci : {0u, 1u, 2u}) {
    std::map<int, std::set<std::uint32_t>> triangles_of_cell;  // a -> owning triangles
    int copies = 0;
    scene.for_each_copy(WorldBox::everything(), [&](const Copy& c) {
      if (c.id.compartment_instance != ci || c.id.instance != 1 || c.id.cell.x != c.id.cell.y) return;
      ++copies;
      triangles_of_cell[c.id.cell.x].insert(c.id.element);
    });
    EXPECT_EQ(copies, 4) << "instance " << ci;  // cells (0,0) .. (3,3), one copy each
    EXPECT_EQ(triangles_of_cell.size(), 4u);
  }
}

TEST(ExplicitScene, CopyNumbersAreUniqueAndBelowTheLimit) {
  const TestPackage pkg(hand_scene());
  const ExplicitScene scene(pkg.package);
  std::set<std::uint64_t> numbers;
  std::size_t copies = 0;
  scene.for_each_copy(WorldBox::everything(), [&](const Copy& c) {
    ++copies;
    numbers.insert(c.number);
    EXPECT_LT(c.number, scene.copy_number_limit());
  });
  EXPECT_EQ(numbers.size(), copies);
  EXPECT_GT(copies, 50u);
}

// Enumerating one instance, or one triangle's membrane copies, yields exactly the copies the whole
// enumeration gives that instance or triangle (the flat level takes triangles one by one).
TEST(ExplicitScene, PerInstanceAndPerTriangleEnumerationsPartitionTheWhole) {
  const TestPackage pkg(hand_scene());
  const ExplicitScene scene(pkg.package);
  const auto key = [](const Copy& c) { return std::pair(c.id.compartment_instance, c.number); };
  std::set<std::pair<std::uint32_t, std::uint64_t>> whole, by_instance, by_triangle, membrane;
  scene.for_each_copy(WorldBox::everything(), [&](const Copy& c) {
    whole.insert(key(c));
    if (c.id.kind == CopyKind::membrane) membrane.insert(key(c));
  });
  const auto instances = pkg.package.records<format::SectionKind::compartment_instances>();
  const auto compartments = pkg.package.records<format::SectionKind::compartments>();
  const auto meshes = pkg.package.records<format::SectionKind::meshes>();
  const auto triangles = pkg.package.records<format::SectionKind::triangles>();
  for (std::uint32_t i = 0; i < instances.size(); ++i) {
    scene.for_each_copy_of(i, WorldBox::everything(), [&](const Copy& c) {
      EXPECT_EQ(c.id.compartment_instance, i);
      by_instance.insert(key(c));
    });
    const gpu::Mesh& mesh = meshes[compartments[instances[i].compartment].mesh];
    for (std::uint32_t tl = 0; tl <= mesh.triangle_count; ++tl)  // one past the last: nothing
      scene.for_each_membrane_copy(i, tl, [&](const Copy& c) {
        EXPECT_EQ(c.id.kind, CopyKind::membrane);
        EXPECT_EQ(c.id.element, mesh.first_triangle + tl);
        EXPECT_LT(c.id.element, triangles.size());
        by_triangle.insert(key(c));
      });
  }
  EXPECT_EQ(by_instance, whole);
  EXPECT_EQ(by_triangle, membrane);
  EXPECT_GT(membrane.size(), 0u);
  EXPECT_LT(membrane.size(), whole.size());  // the hand scene has a core grid too
  EXPECT_THROW(scene.for_each_copy_of(std::uint32_t(instances.size()), WorldBox::everything(), [](const Copy&) {}),
               std::out_of_range);
}

TEST(ExplicitScene, AtomInfoTravelsWithTheAtom) {
  const TestPackage pkg(hand_scene());
  const ExplicitScene scene(pkg.package);
  int iron = 0;
  scene.for_each_atom(WorldBox::everything(), [&](const AtomSample& a) {
    ASSERT_NE(a.info, nullptr);
    if (a.copy->molecule_type == 1) {
      ++iron;
      EXPECT_EQ(std::string(a.info->atom_name, 2), "FE");
      EXPECT_EQ(a.info->residue_number, 1);
    } else {
      EXPECT_EQ(a.info->chain[0], 'A');
    }
  });
  EXPECT_GT(iron, 0);
}

// Culling (instances, triangles, core boxes, copy spheres) must not change the answer: the atoms
// and copies found for a box equal a plain filter over every atom and copy of the scene.
TEST(ExplicitScene, BoxCullingEqualsBruteForceFilter) {
  const TestPackage pkg(hand_scene());
  const ExplicitScene scene(pkg.package);
  const std::vector<Found> all = atoms_in(scene, WorldBox::everything());
  struct Sphere {
    std::uint64_t number;
    glm::dvec3 centre;
    double radius;
  };
  std::vector<Sphere> spheres;
  scene.for_each_copy(WorldBox::everything(), [&](const Copy& c) { spheres.push_back({c.number, c.origin, c.radius}); });

  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  // Boxes around atoms, and boxes with an atom just inside one corner, where a cull that forgets
  // how far a copy reaches out of its triangle, tile or core box would lose it.
  std::vector<WorldBox> boxes;
  for (int trial = 0; trial < 300; ++trial) {
    const glm::dvec3 near = all[std::size_t(unit(rng) * double(all.size()))].position;
    glm::dvec3 centre, half;
    for (int a = 0; a < 3; ++a) centre[a] = near[a] + 30 * (unit(rng) - 0.5), half[a] = 0.5 + 30 * unit(rng);
    boxes.push_back({centre - half, centre + half});
  }
  for (std::size_t i = 0; i < all.size(); i += 2) {
    const glm::dvec3 p = all[i].position, inset(0.01 + 0.2 * unit(rng)), size(1 + 8 * unit(rng));
    boxes.push_back({p - inset, p - inset + size});
    boxes.push_back({p + inset - size, p + inset});
  }
  std::size_t nonempty = 0;
  for (std::size_t trial = 0; trial < boxes.size(); ++trial) {
    const WorldBox& box = boxes[trial];
    std::set<std::pair<std::uint64_t, std::uint32_t>> want, got;
    for (const Found& f : all) {
      const glm::dvec3& p = f.position;
      if (p.x >= box.min.x && p.x <= box.max.x && p.y >= box.min.y && p.y <= box.max.y && p.z >= box.min.z && p.z <= box.max.z)
        want.insert({f.number, f.key.atom});
    }
    for (const Found& f : atoms_in(scene, box)) EXPECT_TRUE(got.insert({f.number, f.key.atom}).second);
    EXPECT_EQ(got, want) << "trial " << trial;
    nonempty += !want.empty();

    std::set<std::uint64_t> want_copies, got_copies;
    for (const Sphere& sp : spheres) {
      double d2 = 0;  // squared distance from the centre to the box
      for (int a = 0; a < 3; ++a) {
        const double excess = std::max({box.min[a] - sp.centre[a], 0.0, sp.centre[a] - box.max[a]});
        d2 += excess * excess;
      }
      if (d2 <= sp.radius * sp.radius) want_copies.insert(sp.number);
    }
    scene.for_each_copy(box, [&](const Copy& c) { got_copies.insert(c.number); });
    EXPECT_EQ(got_copies, want_copies) << "trial " << trial;
  }
  EXPECT_GT(nonempty, boxes.size() / 2);  // most boxes hit atoms
  EXPECT_LT(nonempty, boxes.size());      // and some miss
}

// What the validator does not check but placement needs is refused with a rule, not misplaced.
void expect_refused(void (*mutate)(SampleScene&), const std::string& rule) {
  SampleScene s = hand_scene();
  mutate(s);
  const TestPackage pkg(s);
  try {
    ExplicitScene scene(pkg.package);
    FAIL() << "accepted; expected " << rule;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(rule), std::string::npos) << e.what();
  }
}

TEST(ExplicitScene, RefusesUvOffTheOwnershipGrid) {
  expect_refused([](SampleScene& s) { s.vertex_uvs[1].y = 1e-9f; }, "multiple of 2^-24");
}
TEST(ExplicitScene, RefusesUvBeyondSixteen) {
  expect_refused([](SampleScene& s) { s.vertex_uvs[2] = glm::vec2(16, 2); }, "multiple of 2^-24");
}
TEST(ExplicitScene, RefusesTooSmallReplicationArea) {
  expect_refused([](SampleScene& s) { s.compartments[0].replication_width = 5; }, "replication area of 6×6");
}
TEST(ExplicitScene, RefusesSquareOfAnotherSize) {
  expect_refused([](SampleScene& s) { s.tiles2d[1].size.x = 30; }, "Wang square 1");
}
TEST(ExplicitScene, RefusesCubeOfAnotherSize) {
  expect_refused([](SampleScene& s) { s.tiles3d[2].size.z = 21; }, "Wang cube 2");
}
TEST(ExplicitScene, RefusesSingularInstanceTransform) {
  expect_refused([](SampleScene& s) { s.compartment_instances[3].transform[2] = glm::vec4(0); }, "singular");
}

}  // namespace
}  // namespace nano::explicit_test
