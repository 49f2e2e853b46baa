// What fits is decided from numbers (scene_feasibility.hpp): each rule is checked against its
// analytic bound on a small scene with made-up measures, on both sides of the bound.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "bake/scene/scene_feasibility.hpp"
#include "bake/scene/scene_parser.hpp"
#include "tests/scene/input_error_matchers.hpp"

namespace nano::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

Json base_scene() {
  return parse_json_text(R"({
    "format": "nanouniverse-scene", "version": 1, "seed": 1,
    "molecules": {"spike": {"file": "s.pdb"}, "mprot": {"file": "m.pdb"}, "popc": {"file": "p.pdb"},
                  "hb": {"file": "h.pdb"}, "small": {"file": "x.pdb"}},
    "membranes": {"envelope": {"tile_size": 200,
                               "proteins": [{"molecule": "spike", "density_per_um2": 800},
                                            {"molecule": "mprot", "density_per_um2": 12000, "per_compartment": 100}],
                               "lipids": {"molecule": "popc", "area_per_lipid": 65, "leaflet_offset": 12}}},
    "solubles": {"lumen": {"cube_size": 250, "molecules": [{"molecule": "hb", "concentration_mM": 5},
                                                           {"molecule": "small", "concentration_mM": 1}]}},
    "compartments": {"virion": {"mesh": {"generate": "sphere", "triangles": 1000, "radius": 500},
                                "membrane": "envelope", "soluble": "lumen"}},
    "instances": [{"compartment": "virion", "count": 8, "box": [[0, 0, 0], [10000, 10000, 10000]]}]
  })", "scene.json");
}

SceneDescription scene_with(const std::function<void(Json&)>& modify = {}) {
  Json doc = base_scene();
  if (modify) modify(doc);
  return parse_scene_description(doc, "scene.json");
}

// Made-up but plausible measures, in the order of base_scene's molecules.
std::vector<MoleculeMeasure> measures() {
  MoleculeMeasure spike{.bounding_radius = 90, .lateral_radius = 70, .outer_footprint = 1000, .inner_footprint = 800,
                        .height = 200, .volume = 4e5};
  MoleculeMeasure mprot{.bounding_radius = 30, .lateral_radius = 25, .outer_footprint = 1400, .inner_footprint = 1200,
                        .height = 60, .volume = 5e4};
  MoleculeMeasure popc{.bounding_radius = 15, .lateral_radius = 6, .height = 25, .volume = 600};
  MoleculeMeasure hb{.bounding_radius = 37, .lateral_radius = 30, .height = 70, .volume = 5e4};
  MoleculeMeasure small{.bounding_radius = 10, .lateral_radius = 10, .height = 20, .volume = 2000};
  return {spike, mprot, popc, hb, small};
}

CompartmentMeasure sphere_measure(double radius) {
  return {.area = 4 * kPi * radius * radius, .volume = 4.0 / 3.0 * kPi * radius * radius * radius, .extent = radius,
          .triangles = 1000, .bilayer_thickness = 40};
}

void check_all(const SceneDescription& s, const std::vector<MoleculeMeasure>& m = measures()) {
  check_scene_amounts(s);
  check_molecule_amounts(s, m);
  check_compartment_amounts(s, 0, sphere_measure(500), m);
  check_placement_amounts(s, std::vector<double>{560.0});
}

TEST(SceneFeasibility, AScaleOfARealVirionFits) { EXPECT_NO_THROW(check_all(scene_with())); }

TEST(SceneFeasibility, AProteinDensityBeyondItsFootprintNamesTheLargestThatFits) {
  // The issue's typo: three zeros too many. 1400 Å² a copy, after the spike's 800 x 1000 Å² per µm².
  const auto s = scene_with([](Json& d) { d["membranes"]["envelope"]["proteins"][1]["density_per_um2"] = 1e12; });
  check_scene_amounts(s);
  const double spike_share = 800 * 1000 / 1e8;
  const double most = (1.0 - spike_share) / 1400 * 1e8;  // per µm²: 7.09e4
  EXPECT_INPUT_ERROR(check_molecule_amounts(s, measures()), "membranes.envelope.proteins[1].density_per_um2",
                     "1e12 cannot fit: 'mprot' covers 14 nm² of a leaflet, at most 7.09e4 per µm² beside the proteins listed "
                     "before it (they cover 0.8% of the leaflet)");
  // Just under the bound fits; just over does not.
  const auto at = [&](double density) {
    return scene_with([&](Json& d) { d["membranes"]["envelope"]["proteins"][1]["density_per_um2"] = density; });
  };
  EXPECT_NO_THROW(check_molecule_amounts(at(0.999 * most), measures()));
  EXPECT_THROW(check_molecule_amounts(at(1.001 * most), measures()), InputError);
}

TEST(SceneFeasibility, CopiesPerTileAreWeighedInTheirOwnUnit) {
  // A 200 Å tile is 4e4 Å²: 1400 Å² copies fit 28.57 times, less the spike's 8 %.
  const auto s = scene_with([](Json& d) {
    auto& p = d["membranes"]["envelope"]["proteins"][1];
    p.erase("density_per_um2");
    p["copies_per_tile"] = 1e6;
  });
  EXPECT_INPUT_ERROR(check_molecule_amounts(s, measures()), "membranes.envelope.proteins[1].copies_per_tile",
                     "at most 28.3 per tile");
}

TEST(SceneFeasibility, AProteinOutsideTheBilayerIsWeighedByItsOwnLayer) {
  // No atom in either leaflet: copies side by side fill a slab of their height, V / H = 2000 Å² each.
  auto m = measures();
  m[1].outer_footprint = m[1].inner_footprint = 0;
  m[1].volume = 2000 * 60;
  const auto s = scene_with([](Json& d) { d["membranes"]["envelope"]["proteins"][1]["density_per_um2"] = 6e4; });
  EXPECT_INPUT_ERROR(check_molecule_amounts(s, m), "membranes.envelope.proteins[1].density_per_um2", "at most 50000 per µm²");
}

TEST(SceneFeasibility, AnAmountSoSmallThatTheTileSetHoldsNoCopyIsRefused) {
  // 16 tiles of 200 Å: 6.4e5 Å² = 0.0064 µm², so one copy needs 156 per µm².
  const auto s = scene_with([](Json& d) { d["membranes"]["envelope"]["proteins"][0]["density_per_um2"] = 1e-12; });
  EXPECT_INPUT_ERROR(check_molecule_amounts(s, measures()), "membranes.envelope.proteins[0].density_per_um2",
                     "places no copy: the 16 tiles of 200 Å hold 0.0064 µm² of membrane, so at least 156 per µm²");
  // 16 cubes of 250 Å: 2.5e8 Å³; one copy needs 4e-9 per Å³ = 0.00664 mM.
  const auto t = scene_with([](Json& d) { d["solubles"]["lumen"]["molecules"][1]["concentration_mM"] = 1e-9; });
  EXPECT_INPUT_ERROR(check_molecule_amounts(t, measures()), "solubles.lumen.molecules[1].concentration_mM",
                     "at least 0.00664 mM");
  // Zero means none, and is fine.
  EXPECT_NO_THROW(check_molecule_amounts(
      scene_with([](Json& d) { d["membranes"]["envelope"]["proteins"][0]["density_per_um2"] = 0; }), measures()));
}

TEST(SceneFeasibility, SolublesTogetherFillAtMostCloseMostPackedVolume) {
  // hb: 5e4 Å³ a copy; 5 mM is 3.01e-6 per Å³, 15 % of the volume. 'small' then has 59 % left: 0.59 / 2000 Å³.
  const double per_mM = 6.02214076e-7;
  const double hb_fraction = 5 * per_mM * 5e4;
  const double most_mM = (kMaxSolubleVolumeFraction - hb_fraction) / 2000 / per_mM;
  const auto at = [](double mM) { return scene_with([&](Json& d) { d["solubles"]["lumen"]["molecules"][1]["concentration_mM"] = mM; }); };
  EXPECT_NO_THROW(check_molecule_amounts(at(0.999 * most_mM), measures()));
  EXPECT_INPUT_ERROR(check_molecule_amounts(at(1.001 * most_mM), measures()), "solubles.lumen.molecules[1].concentration_mM",
                     "beside the molecules listed before it");
  // Each alone fits at 40 % of space, together they do not.
  auto m = measures();
  m[4].volume = 5e4;
  const auto both = scene_with([](Json& d) {
    d["solubles"]["lumen"]["molecules"][0]["concentration_mM"] = 13;
    d["solubles"]["lumen"]["molecules"][1]["concentration_mM"] = 13;
  });
  EXPECT_INPUT_ERROR(check_molecule_amounts(both, m), "solubles.lumen.molecules[1].concentration_mM", "cannot fit");
}

TEST(SceneFeasibility, MoleculesLargerThanTheirTileOrCube) {
  EXPECT_INPUT_ERROR(check_molecule_amounts(scene_with([](Json& d) { d["membranes"]["envelope"]["tile_size"] = 120; }), measures()),
                     "membranes.envelope.tile_size", "'spike' spans 140 Å across the membrane, more than a tile; at least 140 Å");
  EXPECT_INPUT_ERROR(check_molecule_amounts(scene_with([](Json& d) { d["solubles"]["lumen"]["cube_size"] = 70; }), measures()),
                     "solubles.lumen.cube_size", "'hb' spans 74 Å, more than a cube");
  EXPECT_NO_THROW(check_molecule_amounts(scene_with([](Json& d) { d["solubles"]["lumen"]["cube_size"] = 75; }), measures()));
}

TEST(SceneFeasibility, TileAndCubeSizesOutsideWhatAnythingFits) {
  for (double edge : {1e-6, 1e-3, 9.9})
    EXPECT_INPUT_ERROR(check_scene_amounts(scene_with([&](Json& d) { d["membranes"]["envelope"]["tile_size"] = edge; })),
                       "membranes.envelope.tile_size", "at least 10 Å");
  for (double edge : {1e6, 1e9})
    EXPECT_INPUT_ERROR(check_scene_amounts(scene_with([&](Json& d) { d["solubles"]["lumen"]["cube_size"] = edge; })),
                       "solubles.lumen.cube_size", "at most 100000 Å");
}

TEST(SceneFeasibility, LipidsNoDenserThanTheirOwnCrossSection) {
  // popc: 600 Å³ over 25 Å: 24 Å² per lipid at least.
  EXPECT_INPUT_ERROR(check_molecule_amounts(scene_with([](Json& d) { d["membranes"]["envelope"]["lipids"]["area_per_lipid"] = 23.9; }),
                                            measures()),
                     "membranes.envelope.lipids.area_per_lipid", "at least 24 Å² per lipid");
  EXPECT_NO_THROW(check_molecule_amounts(scene_with([](Json& d) { d["membranes"]["envelope"]["lipids"]["area_per_lipid"] = 24.1; }),
                                         measures()));
}

TEST(SceneFeasibility, MeshesBeyondFloatPrecisionNameTheSizeKey) {
  EXPECT_INPUT_ERROR(check_scene_amounts(scene_with([](Json& d) { d["compartments"]["virion"]["mesh"]["radius"] = 1e12; })),
                     "compartments.virion.mesh.radius", "at most 1048576 Å");
  const auto s = scene_with([](Json& d) {
    d["compartments"]["virion"]["mesh"] = Json{{"file", "cell.obj"}, {"diameter", 4e6}};
  });
  EXPECT_INPUT_ERROR(check_scene_amounts(s), "compartments.virion.mesh.diameter", "at most 2097152 Å");
  // A file mesh of the same reach, known only once read (its largest side 2 x its reach).
  const auto f = scene_with([](Json& d) { d["compartments"]["virion"]["mesh"] = Json{{"file", "cell.obj"}, {"units", "nm"}}; });
  EXPECT_INPUT_ERROR(check_compartment_amounts(f, 0, sphere_measure(2e6), measures()), "compartments.virion.mesh.units",
                     "the mesh reaches 2000000 Å");
  EXPECT_NO_THROW(check_compartment_amounts(f, 0, sphere_measure(1e6), measures()));
}

TEST(SceneFeasibility, MeshesSmallerThanTheirBilayerOrTooDetailed) {
  EXPECT_INPUT_ERROR(check_compartment_amounts(scene_with(), 0, sphere_measure(10), measures()), "compartments.virion.mesh.radius",
                     "less than the 40 Å thick bilayer it wears; at least 2000 Å");
  EXPECT_INPUT_ERROR(check_scene_amounts(scene_with([](Json& d) { d["compartments"]["virion"]["mesh"]["triangles"] = 5e6; })),
                     "compartments.virion.mesh.triangles", "at most 4000000");
}

TEST(SceneFeasibility, PerCompartmentCountsAgainstTheSurface) {
  // A 500 Å sphere: 3.14e6 Å² holds 2243.99 copies of 1400 Å².
  const auto at = [](int n) { return scene_with([&](Json& d) { d["membranes"]["envelope"]["proteins"][1]["per_compartment"] = n; }); };
  EXPECT_NO_THROW(check_compartment_amounts(at(2243), 0, sphere_measure(500), measures()));
  EXPECT_INPUT_ERROR(check_compartment_amounts(at(2244), 0, sphere_measure(500), measures()),
                     "membranes.envelope.proteins[1].per_compartment", "at most 2243");
}

TEST(SceneFeasibility, RandomPlacementsAgainstTheirBox) {
  // 560 Å spheres in a 10^4 Å box: 0.74 x 1e12 / (4/3 pi 560^3) = 1006 at most.
  const auto at = [](int n) { return scene_with([&](Json& d) { d["instances"][0]["count"] = n; }); };
  EXPECT_NO_THROW(check_placement_amounts(at(1000), std::vector<double>{560.0}));
  EXPECT_INPUT_ERROR(check_placement_amounts(at(1100), std::vector<double>{560.0}), "instances[0].count", "at most 1005 (or a larger box)");
}

TEST(SceneFeasibility, AmountKeysAreInTheUnitTheSceneWrote) {
  const auto s = scene_with([](Json& d) {
    auto& p = d["membranes"]["envelope"]["proteins"][0];
    p.erase("density_per_um2");
    p["copies_per_tile"] = 1;
    auto& m = d["solubles"]["lumen"]["molecules"][1];
    m.erase("concentration_mM");
    m["copies_per_um3"] = 1000;
  });
  EXPECT_EQ(amount_key(s.membranes[0], 0), "membranes.envelope.proteins[0].copies_per_tile");
  EXPECT_EQ(amount_key(s.membranes[0], 1), "membranes.envelope.proteins[1].density_per_um2");
  EXPECT_EQ(amount_key(s.solubles[0], 0), "solubles.lumen.molecules[0].concentration_mM");
  EXPECT_EQ(amount_key(s.solubles[0], 1), "solubles.lumen.molecules[1].copies_per_um3");
}

TEST(SceneFeasibility, MeasuresMustMatchTheScene) {
  EXPECT_THROW(check_molecule_amounts(scene_with(), std::vector<MoleculeMeasure>(2)), std::invalid_argument);
}

}  // namespace
}  // namespace nano::scene
