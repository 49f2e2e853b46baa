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

// Made-up but plausible measures, in the order of base_scene's molecules. The spike reaches 120 Å
// below its centre along its up axis (its stalk) and 80 Å above.
std::vector<MoleculeMeasure> measures() {
  MoleculeMeasure spike{.bounding_radius = 90, .lateral_radius = 70, .outer_footprint = 1000, .inner_footprint = 800,
                        .height = 200, .volume = 4e5, .reach_below = 120, .reach_above = 80};
  MoleculeMeasure mprot{.bounding_radius = 30, .lateral_radius = 25, .outer_footprint = 1400, .inner_footprint = 1200,
                        .height = 60, .volume = 5e4, .reach_below = 30, .reach_above = 30};
  MoleculeMeasure popc{.bounding_radius = 15, .lateral_radius = 6, .height = 25, .volume = 600, .reach_below = 12.5,
                       .reach_above = 12.5};
  MoleculeMeasure hb{.bounding_radius = 37, .lateral_radius = 30, .height = 70, .volume = 5e4, .reach_below = 35,
                     .reach_above = 35};
  MoleculeMeasure small{.bounding_radius = 10, .lateral_radius = 10, .height = 20, .volume = 2000, .reach_below = 10,
                        .reach_above = 10};
  return {spike, mprot, popc, hb, small};
}

// A sphere's measures; no point inside it is farther than its radius from its surface.
CompartmentMeasure sphere_measure(double radius) {
  return {.area = 4 * kPi * radius * radius, .volume = 4.0 / 3.0 * kPi * radius * radius * radius, .extent = radius,
          .triangles = 1000, .bilayer_thickness = 40, .deepest = radius};
}

void check_all(const SceneDescription& s, const std::vector<MoleculeMeasure>& m = measures()) {
  check_scene_amounts(s);
  check_molecule_amounts(s, m);
  check_compartment_amounts(s, 0, sphere_measure(500), m);
  check_compartment_room(s, 0, sphere_measure(500), m);
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

// ---- nothing emptied, nothing detached (#39) ----------------------------------------------------

TEST(SceneFeasibility, ADepthThatDetachesAProteinFromItsBilayerNamesTheDepthsThatReachIt) {
  // The spike spans [d - 120, d + 80] along the normal; the 40 Å bilayer is [-20, 20]: it reaches
  // it for d in [-20 - 80, 20 + 120] = [-100, 140].
  const auto at = [](double depth) {
    return scene_with([&](Json& d) { d["membranes"]["envelope"]["proteins"][0]["depth"] = depth; });
  };
  for (double depth : {-100.0, 0.0, 115.0, 140.0})
    EXPECT_NO_THROW(check_compartment_amounts(at(depth), 0, sphere_measure(500), measures())) << depth;
  for (double depth : {-100.01, 140.01, 1e6, -1e6})
    EXPECT_INPUT_ERROR(check_compartment_amounts(at(depth), 0, sphere_measure(500), measures()),
                       "membranes.envelope.proteins[0].depth", "a depth from -100 to 140 Å");
  EXPECT_INPUT_ERROR(check_compartment_amounts(at(1e6), 0, sphere_measure(500), measures()),
                     "membranes.envelope.proteins[0].depth",
                     "1000000 Å leaves 'spike' detached from its membrane: standing along its up axis at that depth its "
                     "atoms span from 999880 to 1000080 Å from the mid-surface, clear of the 40 Å thick bilayer of "
                     "compartment 'virion' (from -20 to 20 Å about its mid-surface)");
  // The range follows the bilayer's thickness.
  CompartmentMeasure thick = sphere_measure(500);
  thick.bilayer_thickness = 60;
  EXPECT_NO_THROW(check_compartment_amounts(at(150), 0, thick, measures()));
  EXPECT_INPUT_ERROR(check_compartment_amounts(at(150.01), 0, thick, measures()), "membranes.envelope.proteins[0].depth",
                     "a depth from -110 to 150 Å");
  // A protein asked for with no copy may stand anywhere: nothing of it is placed.
  const auto none = scene_with([](Json& d) {
    d["membranes"]["envelope"]["proteins"][0]["depth"] = 1e6;
    d["membranes"]["envelope"]["proteins"][0]["density_per_um2"] = 0;
  });
  EXPECT_NO_THROW(check_compartment_amounts(none, 0, sphere_measure(500), measures()));
}

TEST(SceneFeasibility, LeafletsThatDoNotMeetAtTheMidSurfaceAreRefusedWithTheOffsetsThatWork) {
  // popc reaches 12.5 Å below its centre: at offset o an outer-leaflet lipid's tail ends o - 12.5
  // from the mid-surface (the inner leaflet's mirrored), so the leaflets meet for o in 12.5 ± 3.
  const auto at = [](double offset) {
    return scene_with([&](Json& d) { d["membranes"]["envelope"]["lipids"]["leaflet_offset"] = offset; });
  };
  EXPECT_NO_THROW(check_molecule_amounts(at(12.0), measures()));
  EXPECT_NO_THROW(check_molecule_amounts(at(15.5), measures()));
  EXPECT_NO_THROW(check_molecule_amounts(at(9.5), measures()));
  EXPECT_INPUT_ERROR(check_molecule_amounts(at(15.6), measures()), "membranes.envelope.lipids.leaflet_offset",
                     "the two leaflets stand 6.2 Å apart");
  EXPECT_INPUT_ERROR(check_molecule_amounts(at(15.6), measures()), "membranes.envelope.lipids.leaflet_offset",
                     "; at most 15.5 Å");
  EXPECT_INPUT_ERROR(check_molecule_amounts(at(1e6), measures()), "membranes.envelope.lipids.leaflet_offset",
                     "detached from its membrane");
  EXPECT_INPUT_ERROR(check_molecule_amounts(at(9.4), measures()), "membranes.envelope.lipids.leaflet_offset",
                     "through the other leaflet");
  EXPECT_INPUT_ERROR(check_molecule_amounts(at(9.4), measures()), "membranes.envelope.lipids.leaflet_offset",
                     "; at least 9.5 Å");
  EXPECT_INPUT_ERROR(check_molecule_amounts(at(0.0), measures()), "membranes.envelope.lipids.leaflet_offset",
                     "the leaflets overlap by 25 Å");
}

TEST(SceneFeasibility, APerCompartmentCountOfZeroKeepsNoCopyAndIsRefused) {
  const auto s = scene_with([](Json& d) { d["membranes"]["envelope"]["proteins"][1]["per_compartment"] = 0; });
  EXPECT_INPUT_ERROR(check_molecule_amounts(s, measures()), "membranes.envelope.proteins[1].per_compartment",
                     "0 keeps no copy of 'mprot' on any compartment, though its density_per_um2 asks for 12000; at least 1");
  EXPECT_NO_THROW(check_molecule_amounts(scene_with([](Json& d) {
                                           d["membranes"]["envelope"]["proteins"][1]["per_compartment"] = 0;
                                           d["membranes"]["envelope"]["proteins"][1]["density_per_um2"] = 0;
                                         }),
                                         measures()));
  EXPECT_NO_THROW(check_molecule_amounts(
      scene_with([](Json& d) { d["membranes"]["envelope"]["proteins"][1]["per_compartment"] = 1; }), measures()));
}

TEST(SceneFeasibility, ALipidFillSoSparseThatTheTileSetHoldsNoLipidIsRefused) {
  // 16 tiles of 200 Å hold 6.4e5 Å² of each leaflet: one lipid at most per 6.4e5 Å².
  const auto at = [](double area) {
    return scene_with([&](Json& d) { d["membranes"]["envelope"]["lipids"]["area_per_lipid"] = area; });
  };
  EXPECT_NO_THROW(check_molecule_amounts(at(6.4e5), measures()));
  EXPECT_INPUT_ERROR(check_molecule_amounts(at(6.41e5), measures()), "membranes.envelope.lipids.area_per_lipid",
                     "places no lipid: the 16 tiles of 200 Å hold 640000 Å² of each leaflet, so at most 640000 Å² per lipid");
}

TEST(SceneFeasibility, AClearanceThatLeavesNoRoomInsideNamesTheLargestThatDoes) {
  // No point of a 500 Å sphere is deeper than 500 Å; hb, the largest soluble listed, reaches 37 Å
  // from its centre: a clearance of at most 463 Å leaves it room.
  const auto at = [](double clearance) {
    return scene_with([&](Json& d) { d["solubles"]["lumen"]["clearance"] = clearance; });
  };
  EXPECT_NO_THROW(check_compartment_room(at(463), 0, sphere_measure(500), measures()));
  EXPECT_INPUT_ERROR(check_compartment_room(at(463.01), 0, sphere_measure(500), measures()), "solubles.lumen.clearance",
                     "at most 463 Å");
  EXPECT_INPUT_ERROR(check_compartment_room(at(1e5), 0, sphere_measure(500), measures()), "solubles.lumen.clearance",
                     "100000 Å leaves no room for solubles: no point inside the mesh of compartment 'virion' is farther "
                     "than 500 Å from its surface, and a copy of 'hb' is kept only where its 37 Å bounding sphere stays "
                     "the clearance (and its membrane shell's inner reach) away from it; at most 463 Å");
  // Without hb the smaller molecule bounds it: 500 - 10.
  const auto without_hb = scene_with([](Json& d) {
    d["solubles"]["lumen"]["clearance"] = 480;
    d["solubles"]["lumen"]["molecules"][0]["concentration_mM"] = 0;
  });
  EXPECT_NO_THROW(check_compartment_room(without_hb, 0, sphere_measure(500), measures()));
  // An unmeasured depth (0) checks no room.
  CompartmentMeasure unmeasured = sphere_measure(500);
  unmeasured.deepest = 0;
  EXPECT_NO_THROW(check_compartment_room(at(1e5), 0, unmeasured, measures()));
}

TEST(SceneFeasibility, ACompartmentShallowerThanItsLargestSolubleNamesTheSizeThatHoldsIt) {
  // Deepest point 30 Å from the surface, hb reaches 37 Å: the 500 Å radius must grow by 37 / 30.
  CompartmentMeasure shallow = sphere_measure(500);
  shallow.deepest = 30;
  EXPECT_INPUT_ERROR(check_compartment_room(scene_with(), 0, shallow, measures()), "compartments.virion.mesh.radius",
                     "soluble 'hb' reaches 37 Å from its centre: no copy fits inside; at least 617 Å");
  shallow.deepest = 37;
  EXPECT_NO_THROW(check_compartment_room(scene_with(), 0, shallow, measures()));
}

TEST(SceneFeasibility, AnAmountThatPlacesNoCopyOnOneCompartmentIsRefused) {
  // A 100 Å sphere: 1.2566e5 Å² of membrane and 4.1888e6 Å³ inside, smaller than the tile and cube sets.
  const CompartmentMeasure small = sphere_measure(100);
  const auto spike_at = [](double density) {
    return scene_with([&](Json& d) { d["membranes"]["envelope"]["proteins"][0]["density_per_um2"] = density; });
  };
  // One spike needs 1e8 / 1.2566e5 = 795.8 per µm².
  EXPECT_NO_THROW(check_compartment_room(spike_at(796), 0, small, measures()));
  EXPECT_INPUT_ERROR(check_compartment_room(spike_at(795), 0, small, measures()),
                     "membranes.envelope.proteins[0].density_per_um2",
                     "795 places no copy on compartment 'virion': its 0.00126 µm² of membrane hold 0.999 of 'spike' at "
                     "that density, so at least 796 per µm²");
  // One hb needs 1 / (4.1888e6 Å³ x 6.0221e-7 per Å³ per mM) = 0.3964 mM.
  const auto hb_at = [](double mM) {
    return scene_with([&](Json& d) { d["solubles"]["lumen"]["molecules"][0]["concentration_mM"] = mM; });
  };
  EXPECT_NO_THROW(check_compartment_room(hb_at(0.3965), 0, small, measures()));
  EXPECT_INPUT_ERROR(check_compartment_room(hb_at(0.3963), 0, small, measures()),
                     "solubles.lumen.molecules[0].concentration_mM", "so at least 0.397 mM");
  // One lipid of the fill per leaflet needs an area per lipid of at most the 1.2566e5 Å².
  const auto lipid_at = [](double area) {
    return scene_with([&](Json& d) { d["membranes"]["envelope"]["lipids"]["area_per_lipid"] = area; });
  };
  EXPECT_NO_THROW(check_compartment_room(lipid_at(1.25e5), 0, small, measures()));
  EXPECT_INPUT_ERROR(check_compartment_room(lipid_at(1.26e5), 0, small, measures()),
                     "membranes.envelope.lipids.area_per_lipid", "at most 125000 Å² per lipid");
}

TEST(SceneFeasibility, ALipidMixShareThatRoundsToNoPlaceIsRefused) {
  const auto at = [](double outer, double inner) {
    return scene_with([&](Json& d) {
      auto& m = d["membranes"]["envelope"];
      m.erase("lipids");
      m["lipid_patch"] = Json{{"file", "popc.pdb"}, {"name", "POPC"}};
      m["lipid_mix"] = Json::array({Json{{"file", "pope.pdb"}, {"name", "POPE"}, {"outer", outer}, {"inner", inner}}});
    });
  };
  // 288 places per tile in each leaflet (32 lipids x 3 x 3 repeats): a share takes one from 0.5 / 288.
  const PatchPlaces places{.outer = 288, .inner = 288};
  EXPECT_NO_THROW(check_lipid_mix_amounts(at(0.00174, 0.32), 0, places));
  EXPECT_NO_THROW(check_lipid_mix_amounts(at(0, 0.32), 0, places));
  EXPECT_INPUT_ERROR(check_lipid_mix_amounts(at(0.0017, 0.32), 0, places), "membranes.envelope.lipid_mix[0].outer",
                     "0.0017 places no lipid of 'POPE': a tile of the patch has at most 288 places in the outer leaflet, "
                     "and that share of them rounds to none; at least 0.00174");
  EXPECT_INPUT_ERROR(check_lipid_mix_amounts(at(0.32, 1e-9), 0, places), "membranes.envelope.lipid_mix[0].inner",
                     "at least 0.00174");
  EXPECT_INPUT_ERROR(check_lipid_mix_amounts(at(0.32, 0.3), 0, PatchPlaces{.outer = 288, .inner = 0}),
                     "membranes.envelope.lipid_mix[0].inner", "the patch has no lipid in the inner leaflet");
}

TEST(SceneFeasibility, LeafletSharesMoreThanFivePointsFromTheRequestAreRefusedByKind) {
  const SceneDescription scene = scene_with([](Json& d) {
    auto& m = d["membranes"]["envelope"];
    m.erase("lipids");
    m["lipid_patch"] = Json{{"file", "rbc.pdb"},
                            {"kinds", Json{{"CHL1", Json{{"name", "cholesterol"}}}, {"POPC", Json::object()}}},
                            {"leaflets", Json{{"outer", Json{{"mol_percent", Json{{"cholesterol", 40}, {"POPC", 60}}}, {"area_per_lipid", 45}}},
                                              {"inner", Json{{"mol_percent", Json{{"cholesterol", 0}, {"POPC", 100}}}, {"area_per_lipid", 60}}}}}};
  });
  const LeafletCounts inner{{"POPC", 100}};
  EXPECT_NO_THROW(check_leaflet_shares(scene, 0, {{"cholesterol", 45}, {"POPC", 55}}, inner, "the bake keeps"));
  EXPECT_NO_THROW(check_leaflet_shares(scene, 0, {{"POPC", 65}, {"cholesterol", 35}}, inner, "the bake keeps"));
  EXPECT_INPUT_ERROR(check_leaflet_shares(scene, 0, {{"cholesterol", 34}, {"POPC", 66}}, inner, "the bake keeps"),
                     "membranes.envelope.lipid_patch.leaflets.outer.mol_percent.cholesterol",
                     "40 % of the outer leaflet asked, but the bake keeps 34 % (cholesterol 34 (34 %), POPC 66 (66 %)): "
                     "more than 5 points apart");
  EXPECT_INPUT_ERROR(check_leaflet_shares(scene, 0, {{"POPC", 100}}, inner, "the patch file holds"),
                     "membranes.envelope.lipid_patch.leaflets.outer.mol_percent.cholesterol",
                     "40 % of the outer leaflet asked, but the patch file holds no cholesterol there (POPC 100 (100 %))");
  // A kind the scene asks nothing of (or does not list) may hold at most 5 % of its leaflet.
  EXPECT_NO_THROW(check_leaflet_shares(scene, 0, {{"cholesterol", 40}, {"POPC", 60}}, {{"POPC", 95}, {"cholesterol", 5}}, ""));
  EXPECT_INPUT_ERROR(check_leaflet_shares(scene, 0, {{"cholesterol", 36}, {"POPC", 57}, {"POPS", 7}}, inner, "it holds"),
                     "membranes.envelope.lipid_patch.leaflets.outer.mol_percent.POPS", "0 % of the outer leaflet asked, but it holds 7 %");
  // A membrane that asks no composition passes whatever it holds.
  EXPECT_NO_THROW(check_leaflet_shares(scene_with([](Json&) {}), 0, {{"x", 1}}, {}, ""));
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
  EXPECT_EQ(protein_key(s.membranes[0], 1, "per_compartment"), "membranes.envelope.proteins[1].per_compartment");
}

TEST(SceneFeasibility, MeasuresMustMatchTheScene) {
  EXPECT_THROW(check_molecule_amounts(scene_with(), std::vector<MoleculeMeasure>(2)), std::invalid_argument);
}

}  // namespace
}  // namespace nano::scene
