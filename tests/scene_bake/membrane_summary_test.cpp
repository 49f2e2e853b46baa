// A membrane's lipids against a real bilayer (MembraneSummary): both leaflets together and each
// leaflet against a real one of its own composition, in the area its proteins leave.
#include <gtest/gtest.h>

#include "bake/scene_bake/scene_baker.hpp"

namespace nano::scene_bake {
namespace {

// 0.1 µm²; the outer leaflet asks one molecule per 45 Å² (2.22e6 /µm²), the inner one per 64 Å²
// (1.5625e6 /µm²); proteins take 0.02 µm² of the outer leaflet and 0.01 µm² of the inner one.
MembraneSummary two_compositions(std::uint64_t outer, std::uint64_t inner) {
  MembraneSummary m;
  m.area_um2 = 0.1;
  m.real_outer_per_um2 = 1e8 / 45.0;
  m.real_inner_per_um2 = 1e8 / 64.0;
  m.outer_protein_um2 = 0.02;
  m.inner_protein_um2 = 0.01;
  m.outer_lipids = outer;
  m.inner_lipids = inner;
  return m;
}

TEST(MembraneSummary, EachLeafletIsHeldAgainstARealOneOfItsCompositionBesideItsProteins) {
  // Real: outer 0.08 µm² x 2.22e6 = 177,778; inner 0.09 µm² x 1.5625e6 = 140,625.
  const MembraneSummary full = two_compositions(177'778, 140'625);
  EXPECT_NEAR(full.real_lipids_beside_proteins().outer, 0.08 * 1e8 / 45.0, 1e-6);
  EXPECT_NEAR(full.real_lipids_beside_proteins().inner, 0.09 * 1e8 / 64.0, 1e-6);
  EXPECT_NEAR(full.fraction_of_real_leaflets_beside_proteins().outer, 1.0, 1e-5);
  EXPECT_NEAR(full.fraction_of_real_leaflets_beside_proteins().inner, 1.0, 1e-5);
  EXPECT_NEAR(full.fraction_of_real_bilayer_beside_proteins(), 1.0, 1e-5);
  EXPECT_NEAR(full.real_lipids_per_um2(), 1e8 / 45.0 + 1e8 / 64.0, 1e-6);
  // A thin inner leaflet shows in its own share, and only diluted in the bilayer's.
  const MembraneSummary thin_inner = two_compositions(177'778, 70'312);
  EXPECT_NEAR(thin_inner.fraction_of_real_leaflets_beside_proteins().outer, 1.0, 1e-5);
  EXPECT_NEAR(thin_inner.fraction_of_real_leaflets_beside_proteins().inner, 0.5, 1e-5);
  EXPECT_NEAR(thin_inner.fraction_of_real_bilayer_beside_proteins(), (177'778.0 + 70'312.0) / (177'778.0 + 140'625.0), 1e-5);
}

// On a curved membrane each leaflet is held against a real one of its own surface's area (the mesh
// moved out or in to its lipid centres), proteins taking the same area in it; without those areas
// (a lipid fill) both leaflets take the mesh's.
TEST(MembraneSummary, EachLeafletIsJudgedOnItsOwnSurface) {
  MembraneSummary curved = two_compositions(177'778, 140'625);
  EXPECT_DOUBLE_EQ(curved.leaflet_areas().outer, 0.1);
  EXPECT_DOUBLE_EQ(curved.leaflet_areas().inner, 0.1);
  curved.outer_area_um2 = 0.11;  // a sphere's leaflets: ((R ± d) / R)² of the mid-surface
  curved.inner_area_um2 = 0.09;
  EXPECT_NEAR(curved.real_lipids_beside_proteins().outer, (0.11 - 0.02) * 1e8 / 45.0, 1e-6);
  EXPECT_NEAR(curved.real_lipids_beside_proteins().inner, (0.09 - 0.01) * 1e8 / 64.0, 1e-6);
  EXPECT_NEAR(curved.fraction_of_real_leaflets_beside_proteins().outer, 177'778.0 / (0.09e8 / 45.0), 1e-6);
  EXPECT_NEAR(curved.fraction_of_real_leaflets_beside_proteins().inner, 140'625.0 / (0.08e8 / 64.0), 1e-6);
}

TEST(MembraneSummary, ALeafletProteinsCoverWhollyHasNoShareRatherThanADivisionByZero) {
  MembraneSummary covered = two_compositions(0, 1000);
  covered.outer_protein_um2 = 0.2;  // more than the membrane: no room left in that leaflet
  EXPECT_EQ(covered.fraction_of_real_leaflets_beside_proteins().outer, 0.0);
  EXPECT_GT(covered.fraction_of_real_leaflets_beside_proteins().inner, 0.0);
  EXPECT_EQ(MembraneSummary{}.fraction_of_real_leaflets_beside_proteins().inner, 0.0);
  EXPECT_EQ(MembraneSummary{}.fraction_of_real_bilayer_beside_proteins(), 0.0);
}

}  // namespace
}  // namespace nano::scene_bake
