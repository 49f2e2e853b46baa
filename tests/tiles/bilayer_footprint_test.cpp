#include "bake/tiles/bilayer_footprint.hpp"

#include <cmath>
#include <numbers>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

namespace nano::tiles {
namespace {

constexpr double pi = std::numbers::pi;

MoleculeType atoms(std::vector<AtomSphere> list) {
  MoleculeType t;
  t.name = "probe";
  t.atoms = std::move(list);
  return t;
}

// Area of the union of two discs of radius r whose centres are d apart (lens formula).
double two_disc_union(double r, double d) {
  const double lens = 2.0 * r * r * std::acos(d / (2.0 * r)) - 0.5 * d * std::sqrt(4.0 * r * r - d * d);
  return 2.0 * pi * r * r - lens;
}

TEST(BilayerFootprint, AtomInsideTheSlabCountsItsFullDisc) {
  const MoleculeType t = atoms({{glm::vec3(0.f), 3.f}});
  const double area = leaflet_footprint(t, {0, glm::vec3(5.f, -7.f, 10.f)}, outer_leaflet(20.f), 0.05f);
  EXPECT_NEAR(area, pi * 9.0, 0.02 * pi * 9.0);
}

TEST(BilayerFootprint, AtomCrossingTheSlabFaceCountsItsCrossSection) {
  // Centre 2 Å above the slab's top face: the widest section inside is at the face, radius √(9 − 4).
  const MoleculeType t = atoms({{glm::vec3(0.f), 3.f}});
  const double area = leaflet_footprint(t, {0, glm::vec3(0.f, 0.f, 22.f)}, outer_leaflet(20.f), 0.05f);
  EXPECT_NEAR(area, pi * 5.0, 0.02 * pi * 5.0);
  EXPECT_EQ(leaflet_footprint(t, {0, glm::vec3(0.f, 0.f, 23.5f)}, outer_leaflet(20.f)), 0.0);
  EXPECT_EQ(leaflet_footprint(t, {0, glm::vec3(0.f, 0.f, 10.f)}, inner_leaflet(20.f)), 0.0);
}

TEST(BilayerFootprint, OverlappingAtomsCountTheirUnionOnce) {
  const MoleculeType t = atoms({{glm::vec3(-1.5f, 0.f, 0.f), 2.f}, {glm::vec3(1.5f, 0.f, 0.f), 2.f}});
  const double area = leaflet_footprint(t, {0, glm::vec3(0.f, 0.f, -8.f)}, inner_leaflet(20.f), 0.05f);
  EXPECT_NEAR(area, two_disc_union(2.0, 3.0), 0.02 * two_disc_union(2.0, 3.0));
}

TEST(BilayerFootprint, TurningAboutTheNormalKeepsTheAreaAndTiltingChangesIt) {
  // A rod of atoms along x: standing in the plane it covers a strip, standing along z one disc.
  std::vector<AtomSphere> rod;
  for (int i = -4; i <= 4; ++i) rod.push_back({glm::vec3(2.f * i, 0.f, 0.f), 1.5f});
  const MoleculeType t = atoms(rod);
  const Instance flat{0, glm::vec3(0.f, 0.f, 10.f)};
  Instance turned = flat;
  turned.rotation = glm::angleAxis(0.7f, glm::vec3(0.f, 0.f, 1.f));
  Instance standing = flat;
  standing.rotation = glm::angleAxis(static_cast<float>(pi / 2), glm::vec3(0.f, 1.f, 0.f));
  const double a_flat = leaflet_footprint(t, flat, outer_leaflet(20.f), 0.05f);
  EXPECT_NEAR(leaflet_footprint(t, turned, outer_leaflet(20.f), 0.05f), a_flat, 0.02 * a_flat);
  // Standing, atoms from z = 2 to 18 all lie in the slab and project onto one disc.
  EXPECT_NEAR(leaflet_footprint(t, standing, outer_leaflet(20.f), 0.05f), pi * 2.25, 0.03 * pi * 2.25);
}

}  // namespace
}  // namespace nano::tiles
