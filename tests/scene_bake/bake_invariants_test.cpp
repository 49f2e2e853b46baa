// Nothing emptied (bake_invariants.hpp): the bound on how deep a mesh's inside reaches, a lipid
// patch's places per tile, the checks before the heavy stages on a real mesh, and the end-of-bake
// invariant on summaries built by hand, each on both sides.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "bake/mesh/sphere_mesh.hpp"
#include "bake/scene/scene_parser.hpp"
#include "bake/scene_bake/bake_invariants.hpp"
#include "bake/scene_bake/compartment_mesh.hpp"
#include "common/json_document.hpp"
#include "common/error.hpp"

namespace nano::scene_bake {
namespace {


// An axis-aligned box, outward triangles.
mesh::ProxyMesh box_mesh(glm::dvec3 size) {
  mesh::ProxyMesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back({i & 1 ? size.x : 0.0, i & 2 ? size.y : 0.0, i & 4 ? size.z : 0.0});
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

TEST(BakeInvariants, NoPointInsideAMeshLiesDeeperThanTheBound) {
  // A 100 x 100 x 10 Å slab: its middle plane is 5 Å from both faces.
  const mesh::ProxyMesh slab = box_mesh({100, 100, 10});
  EXPECT_DOUBLE_EQ(deepest_inside(slab, 1e5), 5.0);
  EXPECT_DOUBLE_EQ(deepest_inside(slab, 0.0), 5.0);
  // A cube of 100 Å: the ball of its volume (radius 62 Å) is looser than its half side.
  EXPECT_DOUBLE_EQ(deepest_inside(box_mesh({100, 100, 100}), 1e6), 50.0);
  // A sphere of 450 Å, as the virions are generated: its centre is at least its inradius from every
  // face, and no point lies deeper than the radius of a ball of its volume.
  const mesh::ProxyMesh sphere = mesh::make_sphere_mesh(1280, 450.0);
  const scene::CompartmentMeasure measure = measure_compartment(sphere);
  const double deepest = deepest_inside(sphere, measure.volume);
  EXPECT_LE(deepest, 450.0);
  EXPECT_NEAR(deepest, std::cbrt(3.0 * measure.volume / (4.0 * std::numbers::pi)), 1e-9);
  EXPECT_GT(deepest, 440.0);
  EXPECT_EQ(deepest_inside(mesh::ProxyMesh{}, 1.0), 0.0);
}

TEST(BakeInvariants, APatchGivesEachTileItsLeafletsLipidsTimesItsRepeats) {
  BakedLipidPatch patch;
  patch.period_x = 63.7;
  patch.period_y = 66.9;
  patch.positions = {{1, 2, 18}, {5, 9, 17}, {20, 30, 0.0}, {3, 4, -18}};  // z = 0 counts as outer, as the tiles count it
  const scene::PatchPlaces three = patch_places(patch, 191.1);  // 3 x 3 repeats
  EXPECT_EQ(three.outer, 27.0);
  EXPECT_EQ(three.inner, 9.0);
  const scene::PatchPlaces small = patch_places(patch, 100.0);  // 100 / 63.7 rounds to 2, 100 / 66.9 to 1
  EXPECT_EQ(small.outer, 6.0);
  EXPECT_EQ(small.inner, 2.0);
  EXPECT_EQ(patch_places(patch, 10.0).outer, 3.0);  // at least one repeat
}

scene::SceneDescription scene(const std::string& soluble_extra = "") {
  return scene::parse_scene_description(parse_json_text(R"({
    "format": "nanouniverse-scene", "version": 1,
    "molecules": {"spike": {"file": "s.pdb"}, "mprot": {"file": "m.pdb"}, "hb": {"file": "h.pdb"}, "small": {"file": "x.pdb"}},
    "membranes": {"env": {"tile_size": 191.1,
                          "proteins": [{"molecule": "spike", "density_per_um2": 800, "depth": 115},
                                       {"molecule": "mprot", "density_per_um2": 0}],
                          "lipid_patch": {"file": "popc.pdb", "name": "POPC"},
                          "lipid_mix": [{"file": "pope.pdb", "name": "POPE", "outer": 0.3, "inner": 0.3}]}},
    "solubles": {"lumen": {"cube_size": 250, )" + soluble_extra + R"(
                           "molecules": [{"molecule": "hb", "concentration_mM": 5}, {"molecule": "small", "copies_per_um3": 0}]}},
    "compartments": {"virion": {"mesh": {"generate": "sphere", "triangles": 1280, "radius": 450},
                                "membrane": "env", "soluble": "lumen"},
                     "bare": {"mesh": {"generate": "sphere", "triangles": 1280, "radius": 450}, "soluble": "lumen"}},
    "instances": [{"compartment": "virion"}, {"compartment": "bare", "transform": {"translate": [2000, 0, 0]}}]
  })", "scene.json"), "scene.json");
}

// The four molecules of scene() as the checks measure them: hb and small reach into their cubes.
std::vector<scene::MoleculeMeasure> molecule_measures() {
  std::vector<scene::MoleculeMeasure> molecules(4);
  molecules[2].bounding_radius = 37.0;  // hb
  molecules[3].bounding_radius = 10.0;
  return molecules;
}

// Both compartments of scene() on `mesh`, wearing a 60 Å bilayer.
std::vector<scene::CompartmentMeasure> both_compartments(const mesh::ProxyMesh& mesh) {
  scene::CompartmentMeasure measure = measure_compartment(mesh);
  measure.bilayer_thickness = 60.0;
  return {measure, measure};
}

TEST(BakeInvariants, BeforeTheHeavyStagesAClearanceDeeperThanTheMeshIsRefusedOnTheMeshItself) {
  const mesh::ProxyMesh sphere = mesh::make_sphere_mesh(1280, 450.0);
  const scene::CompartmentMeasure measure = measure_compartment(sphere);
  const std::vector<scene::CompartmentMeasure> meshes = both_compartments(sphere);
  const std::vector<scene::MoleculeMeasure> molecules = molecule_measures();
  const auto mesh_of = [&](std::size_t) -> const mesh::ProxyMesh& { return sphere; };
  const double deepest = deepest_inside(sphere, measure.volume);
  EXPECT_NO_THROW(check_nothing_emptied(scene("\"clearance\": " + std::to_string(deepest - 37.5) + ","), molecules, {},
                                        meshes, mesh_of));
  try {
    check_nothing_emptied(scene("\"clearance\": 1e5,"), molecules, {}, meshes, mesh_of);
    ADD_FAILURE() << "a clearance of 1e5 Å in a 450 Å sphere was not refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "solubles.lumen.clearance");
    EXPECT_NE(e.rule().find("leaves no room for solubles"), std::string::npos) << e.what();
  }
  // A lipid_mix share below one place of 9 x 32 rounds to none.
  BakedLipidPatch patch;
  patch.period_x = 63.7;
  patch.period_y = 66.9;
  for (int i = 0; i < 64; ++i) patch.positions.push_back({i, i, i < 32 ? 18.0 : -18.0});
  scene::SceneDescription sparse = scene();
  sparse.membranes[0].lipid_mix[0].outer = 0.001;
  try {
    check_nothing_emptied(sparse, molecules, {patch}, meshes, mesh_of);
    ADD_FAILURE() << "a share of 0.001 of 288 places was not refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "membranes.env.lipid_mix[0].outer");
    EXPECT_NE(e.rule().find("at most 288 places"), std::string::npos) << e.what();
  }
  sparse.membranes[0].lipid_mix[0].outer = 0.002;
  EXPECT_NO_THROW(check_nothing_emptied(sparse, molecules, {patch}, meshes, mesh_of));
}

// What a bake of scene() that placed everything reports.
BakedScene everything_placed() {
  BakedScene baked;
  CompartmentSummary virion;
  virion.name = "virion";
  virion.copies = {{"spike", 25}, {"POPC", 45000}, {"POPE", 12000}, {"hb", 600}};
  virion.membrane = MembraneSummary{};
  virion.membrane->area_um2 = 0.0254;
  virion.core_boxes_inside = 8;
  virion.core_boxes_boundary = 56;
  CompartmentSummary bare;
  bare.name = "bare";
  bare.copies = {{"hb", 1500}};
  bare.core_boxes_inside = 8;
  bare.core_boxes_boundary = 56;
  baked.compartments = {virion, bare};
  baked.wang_sets = {{"env", {{"spike", 0, 800, 1369, 120}, {"POPC", 1, 2e6, 1.7e6, 40000}, {"POPE", 2, 9e5, 7.8e5, 9000}}},
                     {"lumen", {{"hb", 0, 3.4e6, 3.1e6, 2000}}}};
  return baked;
}

template <class F>
InputError refusal(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError("", "", "");
}

// A core grid wider than a recipe without repeats, for a cube set that cannot repeat, is refused
// with the meshes (not after the membrane's tiles and shells, minutes later), naming what works.
TEST(BakeInvariants, BeforeTheHeavyStagesACoreGridTooWideForItsCubeSetIsRefused) {
  const mesh::ProxyMesh sphere = mesh::make_sphere_mesh(1280, 9000.0);
  const std::vector<scene::CompartmentMeasure> meshes = both_compartments(sphere);
  const std::vector<scene::MoleculeMeasure> molecules = molecule_measures();
  const auto mesh_of = [&](std::size_t) -> const mesh::ProxyMesh& { return sphere; };
  // 18,000 Å across in boxes of 250 Å: floor(18000 / 250) + 1 = 73 boxes, past 64.
  try {
    check_nothing_emptied(scene(), molecules, {}, meshes, mesh_of);
    ADD_FAILURE() << "73 boxes along an axis with 16 of 64 cubes were not refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "solubles.lumen.cubes");
    EXPECT_NE(e.rule().find("73 boxes"), std::string::npos) << e.what();
    EXPECT_NE(e.rule().find("\"cubes\": 64"), std::string::npos) << e.what();
    EXPECT_NE(e.rule().find("\"cube_size\" of at least 286 Å"), std::string::npos) << e.what();
  }
  // Each value it names works: the complete set repeats, and 286 Å boxes make 63 along the axis.
  EXPECT_NO_THROW(check_nothing_emptied(scene("\"cubes\": 64,"), molecules, {}, meshes, mesh_of));
  scene::SceneDescription larger_cubes = scene();
  larger_cubes.solubles[0].cube_size = 286.0;
  EXPECT_NO_THROW(check_nothing_emptied(larger_cubes, molecules, {}, meshes, mesh_of));
}

TEST(BakeInvariants, ABakeThatPlacedEveryListedMoleculePasses) {
  EXPECT_NO_THROW(check_every_molecule_placed(scene(), everything_placed()));
  // mprot and small are listed with no copy asked: none is fine.
  BakedScene more = everything_placed();
  more.compartments[0].copies.emplace_back("mprot", 0);
  EXPECT_NO_THROW(check_every_molecule_placed(scene(), more));
}

TEST(BakeInvariants, AProteinWhoseCopiesWereAllDroppedIsRefusedByItsAmountKey) {
  BakedScene baked = everything_placed();
  baked.compartments[0].copies.erase(baked.compartments[0].copies.begin());  // no spike
  baked.compartments[0].membrane->dropped = {{"spike", 30}};
  baked.compartments[0].membrane->unfit = {{"spike", 30}};
  const InputError e = refusal([&] { check_every_molecule_placed(scene(), baked); });
  EXPECT_EQ(e.file(), "scene.json");
  EXPECT_EQ(e.where(), "membranes.env.proteins[0].density_per_um2");
  EXPECT_EQ(e.rule(), "800 gives compartment 'virion' no copy of 'spike': no copy survived: all 30 the tiles put on its "
                      "surface were dropped (30 where no prism fits)");
  // Some clashing as well.
  baked.compartments[0].membrane->dropped = {{"spike", 35}};
  EXPECT_NE(refusal([&] { check_every_molecule_placed(scene(), baked); }).rule().find(
                "(30 where no prism fits, 5 clashing on the surface or beyond per_compartment)"),
            std::string::npos);
  // None dropped: none landed on the surface.
  baked.compartments[0].membrane->dropped.clear();
  EXPECT_NE(refusal([&] { check_every_molecule_placed(scene(), baked); }).rule().find(
                "the tiles put no copy on its 0.0254 µm² of membrane"),
            std::string::npos);
}

// per_compartment is an upper bound: fewer kept than asked passes, but is named, never silent.
TEST(BakeInvariants, AProteinKeptShortOfItsPerCompartmentCountIsNamed) {
  scene::SceneDescription counted = scene();
  counted.membranes[0].proteins[0].per_compartment = 25;
  EXPECT_TRUE(per_compartment_shortfalls(counted, everything_placed()).empty());  // 25 of 25
  EXPECT_TRUE(per_compartment_shortfalls(scene(), everything_placed()).empty());  // not counted
  BakedScene short_of_it = everything_placed();
  short_of_it.compartments[0].copies[0] = {"spike", 19};
  EXPECT_NO_THROW(check_every_molecule_placed(counted, short_of_it));
  const std::vector<std::string> shortfalls = per_compartment_shortfalls(counted, short_of_it);
  ASSERT_EQ(shortfalls.size(), 1u);
  EXPECT_EQ(shortfalls[0], "membranes.env.proteins[0].per_compartment: compartment 'virion' keeps 19 of the 25 copies of "
                           "'spike' per_compartment asks: its tiles placed no more (pack them denser)");
}

TEST(BakeInvariants, ASolubleMissingFromOneCompartmentIsRefusedNamingThatCompartment) {
  BakedScene baked = everything_placed();
  baked.compartments[1].copies.clear();
  baked.compartments[1].core_boxes_inside = 0;
  baked.compartments[1].core_boxes_boundary = 12;
  const InputError e = refusal([&] { check_every_molecule_placed(scene("\"clearance\": 400,"), baked); });
  EXPECT_EQ(e.where(), "solubles.lumen.molecules[0].concentration_mM");
  EXPECT_EQ(e.rule(), "5 gives compartment 'bare' no copy of 'hb': no copy survived: its core grid has 0 boxes wholly "
                      "inside the mesh and 12 along its surface, and no copy in them stands inside with its bounding "
                      "sphere the clearance (400 Å) away from the surface");
  // The cube set itself held none.
  baked.wang_sets[1].densities[0].copies_in_set = 0;
  baked.wang_sets[1].densities[0].achieved = 0;
  EXPECT_NE(refusal([&] { check_every_molecule_placed(scene(), baked); }).rule().find(
                "the cube set holds no copy of it (the packer reached 0 of the 3.4e+06 per µm³ asked)"),
            std::string::npos);
}

TEST(BakeInvariants, ALipidSpeciesOrThePatchWithoutCopiesIsRefusedByItsKey) {
  BakedScene baked = everything_placed();
  baked.compartments[0].copies.erase(baked.compartments[0].copies.begin() + 2);  // no POPE
  baked.wang_sets[0].densities[2].copies_in_set = 0;
  EXPECT_EQ(refusal([&] { check_every_molecule_placed(scene(), baked); }).where(), "membranes.env.lipid_mix[0].outer");
  // A species asked for in no leaflet is not required.
  scene::SceneDescription unmixed = scene();
  unmixed.membranes[0].lipid_mix[0].outer = unmixed.membranes[0].lipid_mix[0].inner = 0.0;
  EXPECT_NO_THROW(check_every_molecule_placed(unmixed, baked));
  // The base patch keeps what the mix leaves: required unless the mix takes every place of both leaflets.
  baked = everything_placed();
  baked.compartments[0].copies.erase(baked.compartments[0].copies.begin() + 1);  // no POPC
  EXPECT_EQ(refusal([&] { check_every_molecule_placed(scene(), baked); }).where(), "membranes.env.lipid_patch");
  scene::SceneDescription all_mixed = scene();
  all_mixed.membranes[0].lipid_mix[0].outer = all_mixed.membranes[0].lipid_mix[0].inner = 1.0;
  EXPECT_NO_THROW(check_every_molecule_placed(all_mixed, baked));
}

TEST(BakeInvariants, SummariesMustMatchTheScene) {
  BakedScene baked = everything_placed();
  baked.compartments.pop_back();
  EXPECT_THROW(check_every_molecule_placed(scene(), baked), std::invalid_argument);
}

}  // namespace
}  // namespace nano::scene_bake
