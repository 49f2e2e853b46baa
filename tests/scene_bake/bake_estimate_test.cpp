// The measures the feasibility checks weigh amounts against, and the bake's estimate, against
// analytic geometry: sphere and lens volumes, discs, a sphere mesh's area.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bake/mesh/sphere_mesh.hpp"
#include "bake/scene_bake/bake_estimate.hpp"
#include "bake/scene_bake/bake_progress.hpp"
#include "bake/scene_bake/compartment_mesh.hpp"
#include "bake/scene_bake/molecule_measures.hpp"
#include "bake/scene_bake/named_totals.hpp"
#include "bake/tiles/wang_sets.hpp"

namespace nano::scene_bake {
namespace {


structure::Atom atom(glm::dvec3 p, double r) {
  structure::Atom a;
  a.position = p;
  a.radius = r;
  return a;
}

TEST(MoleculeMeasures, UnionVolumeOfOneSphereAndOfTwoOverlapping) {
  // Counted on a 0.5 Å grid: within 5 % for one atom-sized sphere, within 1 % for a large one.
  const auto ball = [](double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; };
  EXPECT_NEAR(union_volume({atom({0, 0, 0}, 2.0)}), ball(2.0), 0.05 * ball(2.0));
  EXPECT_NEAR(union_volume({atom({0.3, 0.1, 0.7}, 20.0)}), ball(20.0), 0.01 * ball(20.0));
  // Two spheres d apart overlap in a lens of pi (4r + d)(2r - d)^2 / 12.
  const double r = 2.0, d = 2.0;
  const double two = 2 * ball(r) - std::numbers::pi * (4 * r + d) * (2 * r - d) * (2 * r - d) / 12.0;
  EXPECT_NEAR(union_volume({atom({0, 0, 0}, r), atom({d, 0, 0}, r)}), two, 0.05 * two);
  EXPECT_EQ(union_volume({}), 0.0);
}

BakedMolecule rod_molecule(glm::dvec3 up) {
  // Five carbons of radius 1.7 along z, 2 Å apart, centred: 11.4 Å long, 1.7 Å from its axis.
  BakedMolecule m;
  m.name = "rod";
  for (int i = -2; i <= 2; ++i) m.atoms.push_back(atom({0, 0, 2.0 * i}, 1.7));
  m.properties.bounding_radius = 4.0 + 1.7;
  m.up = up;
  return m;
}

scene::SceneDescription one_molecule_scene(double depth) {
  scene::SceneDescription s;
  s.molecules.push_back({.name = "rod"});
  scene::MembraneDescription membrane;
  membrane.name = "m";
  membrane.tile_size = 100;
  membrane.proteins.push_back({.molecule = {"rod", 0}, .abundance = {}, .depth = depth});
  s.membranes.push_back(membrane);
  return s;
}

// one_molecule_scene with the rod at 1000 per µm² on a membrane worn by one compartment, one instance.
scene::SceneDescription one_membrane_cell_scene() {
  scene::SceneDescription s = one_molecule_scene(0.0);
  s.membranes[0].proteins[0].abundance = {scene::SurfaceAbundance::Unit::per_um2, 1000.0};
  scene::CompartmentDescription c;
  c.name = "cell";
  c.membrane = scene::NameRef{"m", 0};
  s.compartments.push_back(c);
  s.instances.push_back(scene::ExplicitInstance{.compartment = {"cell", 0}});
  return s;
}

// The work the estimate gives the stage named, or -1 when it has no such stage.
double stage_work(const BakeEstimate& e, const std::string& stage_name) {
  for (const StageEstimate& stage : e.stages)
    if (stage.stage == stage_name) return stage.work;
  return -1.0;
}

TEST(MoleculeMeasures, AStandingRodMeasuresItsLengthItsReachAndItsDiscInEachLeaflet) {
  const auto measures = measure_molecules(one_molecule_scene(0.0), {rod_molecule({0, 0, 1})});
  ASSERT_EQ(measures.size(), 1u);
  const scene::MoleculeMeasure& m = measures[0];
  EXPECT_NEAR(m.height, 8.0 + 2 * 1.7, 1e-9);
  EXPECT_NEAR(m.lateral_radius, 1.7, 1e-9);
  EXPECT_NEAR(m.bounding_radius, 5.7, 1e-9);
  // Standing in the bilayer, it cuts both leaflets in a disc of radius 1.7 Å.
  EXPECT_NEAR(m.outer_footprint, std::numbers::pi * 1.7 * 1.7, 0.1 * std::numbers::pi * 1.7 * 1.7);
  EXPECT_NEAR(m.inner_footprint, m.outer_footprint, 1e-9);
  // Lying down (up along x), its shadow on the membrane is the whole rod, 11.4 x 3.4 Å at most.
  const auto lying = measure_molecules(one_molecule_scene(0.0), {rod_molecule({1, 0, 0})});
  EXPECT_GT(lying[0].outer_footprint, 25.0);
  EXPECT_NEAR(lying[0].lateral_radius, 4.0 + 1.7, 1e-9);
  // Lifted 100 Å above the bilayer it takes none of it.
  const auto above = measure_molecules(one_molecule_scene(100.0), {rod_molecule({0, 0, 1})});
  EXPECT_EQ(above[0].outer_footprint, 0.0);
  EXPECT_EQ(above[0].inner_footprint, 0.0);
}

TEST(BakeEstimate, CopiesFollowTheDensityTimesTheAreaAndTheConcentrationTimesTheVolume) {
  scene::SceneDescription s = one_molecule_scene(0.0);
  s.membranes[0].proteins[0].abundance = {scene::SurfaceAbundance::Unit::per_um2, 1000.0};
  scene::SolubleDescription lumen;
  lumen.name = "lumen";
  lumen.cube_size = 100;
  lumen.molecules.push_back({.molecule = {"rod", 0}, .abundance = {scene::VolumeAbundance::Unit::millimolar, 1.0}});
  s.solubles.push_back(lumen);
  scene::CompartmentDescription c;
  c.name = "cell";
  c.membrane = scene::NameRef{"m", 0};
  c.soluble = scene::NameRef{"lumen", 0};
  s.compartments.push_back(c);
  s.instances.push_back(scene::ExplicitInstance{.compartment = {"cell", 0}});
  const mesh::ProxyMesh sphere = mesh::make_sphere_mesh(5000, 1000.0);
  scene::CompartmentMeasure measure = measure_compartment(sphere);
  measure.bilayer_thickness = 40.0;
  const BakeEstimate e = estimate_bake(s, {rod_molecule({0, 0, 1})}, {std::nullopt}, {{measure, 0.0}}, 2);
  ASSERT_EQ(e.compartments.size(), 1u);
  EXPECT_NEAR(e.compartments[0].area_um2, measure.area / 1e8, 1e-12);
  EXPECT_NEAR(e.compartments[0].area_um2, 4 * std::numbers::pi * 1e6 / 1e8, 0.01 * 4 * std::numbers::pi * 1e6 / 1e8);
  ASSERT_GE(e.compartments[0].copies.size(), 1u);
  EXPECT_EQ(e.compartments[0].copies[0].first, "rod");
  // 1000 per µm² on the surface plus 1 mM (6.02e-7 per Å³) in the volume inside the membrane: the
  // solubles' centres keep half the bilayer (20 Å) and their own radius (5.7 Å) from the mesh.
  const double inside = measure.volume - measure.area * (20.0 + 5.7);
  const double expected = 1000.0 * measure.area / 1e8 + 6.02214076e-7 * inside;
  EXPECT_NEAR(e.compartments[0].copies[0].second, expected, 0.01 * expected);
  EXPECT_EQ(e.instances, 1u);
  EXPECT_GT(e.peak_bytes, 0.0);
  EXPECT_GT(e.cpu_seconds, 0.0);
  EXPECT_LE(e.wall_seconds, e.cpu_seconds);
}

// The shells' work: every copy the triangles own before any is dropped (all of a lipid fill's places,
// not only those kept), on a membrane checked everywhere, with each lipid's alternates put aside
// (tiles::kAlternatesPerLaidLipid, 0.3 of a checked copy's work each); a quarter of the copies on a
// membrane checked on a quarter of its area (membrane_surface.hpp) and without seams, and no alternates.
TEST(BakeEstimate, ShellsCheckWhatTheCheckedTrianglesOwn) {
  scene::SceneDescription s = one_membrane_cell_scene();
  s.membranes[0].lipids = scene::LipidFill{.molecule = {"rod", 0}, .area_per_lipid = 65.0};
  scene::CompartmentMeasure measure = measure_compartment(mesh::make_sphere_mesh(5000, 1000.0));
  const double lipids = measure.area * 2.0 / 65.0;
  const double owned = lipids + measure.area * 1000.0 / 1e8;
  const auto shells_work = [&](double checked_share) {
    return stage_work(estimate_bake(s, {rod_molecule({0, 0, 1})}, {std::nullopt}, {{measure, 0.0, checked_share}}, 2), "shells");
  };
  const double alternates = 0.3 * tiles::kAlternatesPerLaidLipid * lipids;
  EXPECT_NEAR(shells_work(1.0), owned + alternates, 1e-6 * owned);
  EXPECT_NEAR(shells_work(0.25), 0.25 * owned, 1e-6 * owned);
}

// The tile sets' time follows the atoms the packers place one by one (the membrane's proteins), not
// a lipid fill's, which are laid in rows; the package's work counts both.
TEST(BakeEstimate, TileSetsCostThePackedAtomsNotTheLipids) {
  scene::SceneDescription s = one_membrane_cell_scene();
  const scene::CompartmentMeasure measure = measure_compartment(mesh::make_sphere_mesh(5000, 1000.0));
  const auto work = [&](const std::string& name) {
    return stage_work(estimate_bake(s, {rod_molecule({0, 0, 1})}, {std::nullopt}, {{measure, 0.0}}, 2), name);
  };
  const scene::MembraneDescription& m = s.membranes[0];
  const double set_area = m.tiles * m.tile_size * m.tile_size;
  const double atoms = static_cast<double>(rod_molecule({0, 0, 1}).atoms.size());
  const double protein_atoms = set_area * 1000.0 / 1e8 * atoms;
  EXPECT_NEAR(work("tile sets"), protein_atoms, 1e-9 * protein_atoms);
  EXPECT_NEAR(work("package content"), protein_atoms, 1e-9 * protein_atoms);
  s.membranes[0].lipids = scene::LipidFill{.molecule = {"rod", 0}, .area_per_lipid = 65.0};
  EXPECT_NEAR(work("tile sets"), protein_atoms, 1e-9 * protein_atoms);
  const double with_lipids = protein_atoms + set_area * 2.0 / 65.0 * atoms;
  EXPECT_NEAR(work("package content"), with_lipids, 1e-9 * with_lipids);
}

// A tile set the bake cache serves costs no packing; what it holds still goes into the package.
TEST(BakeEstimate, ACachedTileSetCostsNoPacking) {
  const scene::SceneDescription s = one_membrane_cell_scene();
  const scene::CompartmentMeasure measure = measure_compartment(mesh::make_sphere_mesh(5000, 1000.0));
  const auto work = [&](const std::string& name, const std::vector<bool>& cached) {
    return stage_work(estimate_bake(s, {rod_molecule({0, 0, 1})}, {std::nullopt}, {{measure, 0.0}}, 2, cached), name);
  };
  ASSERT_GT(work("tile sets", {}), 0.0);
  EXPECT_EQ(work("tile sets", {false}), work("tile sets", {}));
  EXPECT_EQ(work("tile sets", {true}), 0.0);
  EXPECT_EQ(work("package content", {true}), work("package content", {}));
}

TEST(BakeEstimate, MembraneCopiesForPruningAddTheLipidsAndEveryProtein) {
  // 1e6 Å² (0.01 µm²) with 65 Å² lipids in two leaflets, 1000 per µm² and 0.5 per 100 Å tile.
  scene::MembraneDescription m = one_molecule_scene(0.0).membranes[0];
  m.proteins[0].abundance = {scene::SurfaceAbundance::Unit::per_um2, 1000.0};
  m.proteins.push_back({.molecule = {"rod", 0}, .abundance = {scene::SurfaceAbundance::Unit::per_tile, 0.5}});
  m.lipids = scene::LipidFill{.molecule = {"rod", 0}, .area_per_lipid = 65.0};
  EXPECT_NEAR(membrane_copies_for_pruning(1e6, m, std::nullopt), 1e6 * (2.0 / 65.0 + 1000.0 / 1e8 + 0.5 / 1e4), 1e-6);
  // A patch of 4 lipids in a 10 x 20 Å box: 0.02 per Å².
  BakedLipidPatch patch;
  patch.molecules = {0, 0, 0, 0};
  patch.period_x = 10.0;
  patch.period_y = 20.0;
  m.lipids.reset();
  EXPECT_NEAR(membrane_copies_for_pruning(1e6, m, patch), 1e6 * (0.02 + 1000.0 / 1e8 + 0.5 / 1e4), 1e-6);
}

TEST(NamedTotals, EntriesKeepFirstAppearanceOrderAndStartAtZero) {
  std::vector<std::pair<std::string, double>> list;
  named_entry(list, "b") += 2.0;
  named_entry(list, "a") += 1.0;
  named_entry(list, "b") += 3.0;
  named_entry(list, "c") = 7.0;
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[0], (std::pair<std::string, double>{"b", 5.0}));
  EXPECT_EQ(list[1], (std::pair<std::string, double>{"a", 1.0}));
  EXPECT_EQ(list[2], (std::pair<std::string, double>{"c", 7.0}));
}

TEST(BakeEstimate, OverTheBudgetNamesTheLargestPartAndWhatShrinksIt) {
  BakeEstimate e;
  e.memory = {{"the baker itself", 1e8, ""}, {"meshes (1e8 triangles)", 3e10, "fewer triangles"}, {"instances (2)", 1e3, "fewer"}};
  e.peak_bytes = 3.01e10;
  const std::string text = over_memory_budget(e, 8e9);
  EXPECT_NE(text.find("about 30.10 GB"), std::string::npos) << text;
  EXPECT_NE(text.find("more than the 8.00 GB allowed"), std::string::npos) << text;
  EXPECT_NE(text.find("meshes (1e8 triangles): 30.00 GB; to shrink it: fewer triangles"), std::string::npos) << text;
  EXPECT_EQ(text.find("instances"), std::string::npos) << text;  // too small to matter
}

TEST(BakeEstimate, ByteSizesAsUsersWriteThem) {
  EXPECT_EQ(parse_byte_size("2000000"), 2e6);
  EXPECT_EQ(parse_byte_size("512M"), 512.0 * 1024 * 1024);
  EXPECT_EQ(parse_byte_size("8G"), 8.0 * 1024 * 1024 * 1024);
  EXPECT_EQ(parse_byte_size("1.5GiB"), 1.5 * 1024 * 1024 * 1024);
  EXPECT_EQ(parse_byte_size("24gb"), 24.0 * 1024 * 1024 * 1024);
  EXPECT_EQ(parse_byte_size("1T"), 1024.0 * 1024 * 1024 * 1024);
  for (const char* bad : {"", "lots", "8X", "-1G", "0", "nan", "1e400"}) EXPECT_FALSE(parse_byte_size(bad)) << bad;
}

TEST(BakeEstimate, ThisProcessIsMeasured) {
  EXPECT_GT(available_memory_bytes(), 0.0);
  EXPECT_GT(peak_resident_bytes(), 1e6);
  EXPECT_GE(process_cpu_seconds(), 0.0);
}

TEST(BakeProgress, LinesSayPercentElapsedAndRemaining) {
  EXPECT_EQ(progress_line("shells", 0, 0, 0.4), "nanobake: shells  0.4 s");
  EXPECT_EQ(progress_line("shells", 50, 200, 0.5), "nanobake: shells   25%  0.5 s");
  // A quarter done in 3 s: 9 s left.
  EXPECT_EQ(progress_line("tile sets", 50, 200, 3.0), "nanobake: tile sets   25%  3.0 s, about 9 s left");
  EXPECT_EQ(progress_line("tile sets", 200, 200, 12.0), "nanobake: tile sets  100%  12.0 s");
}

}  // namespace
}  // namespace nano::scene_bake
