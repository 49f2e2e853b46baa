// Mesh packing, compartment meshes and the Wang-set glue of the scene baker.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include <gtest/gtest.h>

#include "bake/mesh/mesh_reader.hpp"
#include "bake/mesh/sphere_mesh.hpp"
#include "bake/scene_bake/compartment_mesh.hpp"
#include "bake/scene_bake/mesh_packing.hpp"
#include "bake/scene_bake/wang_bake.hpp"
#include "bake/tiles/wang_colouring.hpp"
#include "common/error.hpp"
#include "format/draco_mesh_sections.hpp"

namespace {

namespace fs = std::filesystem;
using namespace nano;

TEST(MeshPacking, EveryCornerKeepsItsPositionUvAndNormal) {
  const mesh::ProxyMesh sphere = mesh::make_sphere_mesh(300, 100.0);
  const scene_bake::PackedMesh packed = scene_bake::pack_mesh(sphere);
  ASSERT_EQ(packed.triangles.size(), sphere.triangles.size());
  std::set<std::array<std::uint32_t, 3>> distinct_corners;
  for (std::size_t t = 0; t < sphere.triangles.size(); ++t) {
    const std::uint32_t v[3] = {packed.triangles[t].v0, packed.triangles[t].v1, packed.triangles[t].v2};
    for (int c = 0; c < 3; ++c) {
      distinct_corners.insert({sphere.triangles[t][c], sphere.uv_triangles[t][c], sphere.normal_triangles[t][c]});
      ASSERT_LT(v[c], packed.positions.size());
      EXPECT_EQ(glm::vec3(packed.positions[v[c]]), glm::vec3(sphere.corner_position(t, c)));
      EXPECT_EQ(packed.uvs[v[c]], glm::vec2(sphere.corner_uv(t, c)));
      EXPECT_EQ(glm::vec3(packed.normals[v[c]]), glm::vec3(sphere.corner_normal(t, c)));
    }
  }
  // One package vertex per distinct corner combination: seams split, nothing else does.
  EXPECT_EQ(packed.positions.size(), distinct_corners.size());
  EXPECT_GT(packed.positions.size(), sphere.positions.size());
  for (const glm::vec4& p : packed.positions) {
    EXPECT_LE(p.x, packed.aabb_max.x);
    EXPECT_GE(p.z, packed.aabb_min.z);
  }
  double max_x = -1e300;
  for (const glm::dvec3& p : sphere.positions) max_x = std::max(max_x, p.x);
  EXPECT_FLOAT_EQ(packed.aabb_max.x, static_cast<float>(max_x));
}

TEST(MeshPacking, RefusesAMeshWithoutUvs) {
  mesh::ProxyMesh sphere = mesh::make_sphere_mesh(48, 10.0);
  sphere.uv_triangles.clear();
  EXPECT_THROW(scene_bake::pack_mesh(sphere), std::invalid_argument);
}

// On Draco's grids a mesh moves by at most half a grid step, keeps its topology and every corner's
// attributes, and packs in canonical order to exactly what a Draco package decodes to.
TEST(MeshPacking, StorageGridsMoveLittleAndPackToWhatDracoDecodes) {
  const mesh::ProxyMesh sphere = mesh::make_sphere_mesh(1200, 3000.0);
  const mesh::ProxyMesh moved = scene_bake::on_storage_grids(sphere);
  ASSERT_EQ(moved.triangles.size(), sphere.triangles.size());
  EXPECT_EQ(moved.positions.size(), sphere.positions.size());  // welded as before: nothing merged
  const float step = format::storage_position_step(3000.0);
  EXPECT_EQ(step, 1.f / 32);
  // Triangles are reordered and rotated: each moved triangle is matched to the input triangle (and
  // rotation) whose corners lie nearest, found through its centroid on a 1 Å grid.
  const auto cell = [](const glm::dvec3& p) {
    return std::array<std::int64_t, 3>{std::llround(std::floor(p.x)), std::llround(std::floor(p.y)), std::llround(std::floor(p.z))};
  };
  const auto centroid = [](const mesh::ProxyMesh& m, std::size_t t) {
    return (m.corner_position(t, 0) + m.corner_position(t, 1) + m.corner_position(t, 2)) / 3.0;
  };
  std::map<std::array<std::int64_t, 3>, std::vector<std::size_t>> by_cell;
  for (std::size_t t = 0; t < sphere.triangles.size(); ++t) by_cell[cell(centroid(sphere, t))].push_back(t);
  double worst_move = 0.0, worst_uv = 0.0, worst_angle = 0.0;
  std::set<std::size_t> matched;
  for (std::size_t t = 0; t < moved.triangles.size(); ++t) {
    const std::array<std::int64_t, 3> home = cell(centroid(moved, t));
    double best = 1e300;
    std::size_t best_t = 0;
    int best_r = 0;
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = by_cell.find({home[0] + dx, home[1] + dy, home[2] + dz});
          if (it == by_cell.end()) continue;
          for (const std::size_t u : it->second)
            for (int r = 0; r < 3; ++r) {
              double d = 0.0;
              for (int c = 0; c < 3; ++c) d = std::max(d, glm::length(moved.corner_position(t, c) - sphere.corner_position(u, (c + r) % 3)));
              if (d < best) best = d, best_t = u, best_r = r;
            }
        }
    matched.insert(best_t);
    worst_move = std::max(worst_move, best);
    for (int c = 0; c < 3; ++c) {
      const int d = (c + best_r) % 3;
      worst_uv = std::max(worst_uv, glm::length(moved.corner_uv(t, c) - sphere.corner_uv(best_t, d)));
      const glm::dvec3 a = moved.corner_normal(t, c), b = sphere.corner_normal(best_t, d);
      worst_angle = std::max(worst_angle, std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
      for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(std::fmod(moved.corner_position(t, c)[axis], double(step)), 0.0);
    }
  }
  EXPECT_EQ(matched.size(), sphere.triangles.size());  // one to one
  EXPECT_LE(worst_move, std::sqrt(3.0) * step / 2);
  EXPECT_LE(worst_uv, std::sqrt(2.0) * 0x1p-25 + 1e-12);
  EXPECT_LT(worst_angle, 1e-4);
  const mesh::MeshReport report = mesh::check_mesh(moved, mesh::CheckOptions{});
  EXPECT_TRUE(report.usable());

  // Packed canonically, the arrays are what Draco streams decode to, bit for bit.
  const scene_bake::PackedMesh packed = scene_bake::pack_mesh_canonical(moved);
  gpu::Mesh record{};
  record.vertex_count = std::uint32_t(packed.positions.size());
  record.triangle_count = std::uint32_t(packed.triangles.size());
  const format::DracoEncoding draco =
      format::encode_draco_meshes(std::span(&record, 1), packed.positions, packed.normals, packed.uvs, packed.triangles);
  ASSERT_TRUE(draco.why.empty()) << draco.why;
  const format::MeshArrays decoded = format::decode_draco_meshes(draco.section, std::span(&record, 1), 1u << 20, 1u << 20);
  EXPECT_TRUE(format::same_bits(decoded, {packed.positions, packed.normals, packed.uvs, packed.triangles}));
  // The exact input packs to arrays Draco cannot store exactly (floats off every coarse grid).
  const scene_bake::PackedMesh exact = scene_bake::pack_mesh(sphere);
  gpu::Mesh exact_record{};
  exact_record.vertex_count = std::uint32_t(exact.positions.size());
  exact_record.triangle_count = std::uint32_t(exact.triangles.size());
  EXPECT_NE(format::encode_draco_meshes(std::span(&exact_record, 1), exact.positions, exact.normals, exact.uvs, exact.triangles).why, "");
  // A mesh in another order is refused by pack_mesh_canonical (its shells would not be parallel).
  EXPECT_THROW(scene_bake::pack_mesh_canonical(sphere), std::logic_error);
}

// A generated 300-triangle sphere of radius 400 Å, as a virion's compartment.
scene::CompartmentDescription sphere_compartment() {
  scene::CompartmentDescription c;
  c.name = "virion";
  c.mesh.kind = scene::MeshSource::Kind::sphere;
  c.mesh.triangles = 300;
  c.mesh.radius = 400.0;
  return c;
}

TEST(CompartmentMesh, PutOnStorageGridsSaysWhatItDid) {
  scene_bake::CompartmentMesh m = scene_bake::load_compartment_mesh(sphere_compartment());
  EXPECT_FALSE(m.on_storage_grids);
  scene_bake::put_on_storage_grids(m);
  EXPECT_TRUE(m.on_storage_grids);
  EXPECT_TRUE(m.report.usable());
  EXPECT_NE(m.storage.find("0.03125 Å"), std::string::npos) << m.storage;
  EXPECT_NO_THROW(scene_bake::pack_mesh_canonical(m.mesh));
}

TEST(CompartmentMesh, ScalesPositionsOnly) {
  mesh::ProxyMesh sphere = mesh::make_sphere_mesh(48, 10.0);
  const auto uvs = sphere.uvs;
  const auto normals = sphere.normals;
  const glm::dvec3 p = sphere.positions[3];
  scene_bake::scale_mesh(sphere, 2.5);
  EXPECT_EQ(sphere.positions[3], p * 2.5);
  EXPECT_EQ(sphere.uvs, uvs);
  EXPECT_EQ(sphere.normals, normals);
}

TEST(CompartmentMesh, GeneratedSphereIsScaledAndChecked) {
  scene::CompartmentDescription c = sphere_compartment();
  c.scale = 1.5;
  const scene_bake::CompartmentMesh m = scene_bake::load_compartment_mesh(c);
  EXPECT_TRUE(m.report.usable());
  double r = 0.0;
  for (const glm::dvec3& p : m.mesh.positions) r = std::max(r, glm::length(p));
  EXPECT_NEAR(r, 600.0, 1e-9);
  EXPECT_NE(m.origin.find("sphere"), std::string::npos);
}

// A unit tetrahedron written as OBJ without UVs (volume 1/6, largest side 1).
fs::path tetrahedron_file(const char* name, bool open = false) {
  const fs::path path = fs::temp_directory_path() / name;
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\n" << (open ? "" : "f 3 1 4\n");
  return path;
}

scene::CompartmentDescription tetrahedron(const fs::path& path) {
  scene::CompartmentDescription c;
  c.name = "tetra";
  c.mesh.kind = scene::MeshSource::Kind::file;
  c.mesh.file = path;
  return c;
}

std::string load_error(const scene::CompartmentDescription& c) {
  try {
    scene_bake::load_compartment_mesh(c);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(CompartmentMesh, UnusableMeshNamesTheFileAndTheProblem) {
  scene::CompartmentDescription c = tetrahedron(tetrahedron_file("nano_scene_bake_no_uvs.obj"));
  c.mesh.uv = scene::MeshSource::Uv::keep;  // the scene forbids the baker's charts
  const std::string what = load_error(c);
  EXPECT_NE(what.find("nano_scene_bake_no_uvs.obj"), std::string::npos) << what;
  EXPECT_NE(what.find("no UVs"), std::string::npos) << what;
  EXPECT_NE(what.find("tetra"), std::string::npos) << what;
}

// A mesh "repair" could not make usable is refused with what the repair did (here: nothing to mend).
TEST(CompartmentMesh, RefusalAfterRepairSaysWhatTheRepairDid) {
  scene::CompartmentDescription c = tetrahedron(tetrahedron_file("nano_scene_bake_repaired_no_uvs.obj"));
  c.mesh.uv = scene::MeshSource::Uv::keep;
  c.mesh.repair = true;
  const std::string what = load_error(c);
  EXPECT_NE(what.find("no UVs"), std::string::npos) << what;
  EXPECT_NE(what.find("repair: nothing to mend"), std::string::npos) << what;
  c.mesh.repair = false;
  EXPECT_EQ(load_error(c).find("repair:"), std::string::npos);
}

// Without UVs the baker makes them and the result passes check-mesh: a tetrahedron's face normals
// lie 109.5° apart, so two faces stay within 60° (54.7° each) of their mean and pair up: 2 charts.
TEST(CompartmentMesh, MeshWithoutUvsGetsCharts) {
  const scene_bake::CompartmentMesh m = scene_bake::load_compartment_mesh(tetrahedron(tetrahedron_file("nano_scene_bake_charts.obj")));
  ASSERT_TRUE(m.charts.has_value());
  EXPECT_EQ(m.charts->charts.size(), 2u);
  EXPECT_TRUE(m.report.usable());
  EXPECT_TRUE(m.mesh.has_uvs());
  EXPECT_NE(m.uv_origin.find("the mesh has none"), std::string::npos) << m.uv_origin;
}

// A surface with a hole is refused for what it is (a border), not for its missing UVs.
TEST(CompartmentMesh, OpenMeshWithoutUvsIsRefusedForItsHole) {
  const std::string what = load_error(tetrahedron(tetrahedron_file("nano_scene_bake_open.obj", true)));
  EXPECT_NE(what.find("border edge"), std::string::npos) << what;
  EXPECT_EQ(what.find("no UVs"), std::string::npos) << what;
}

// A mesh "repair" will not mend (a fin: three faces on one edge) is refused by the repair itself,
// from the mesh file and the compartment it was read for.
TEST(CompartmentMesh, RepairRefusalNamesTheFileAndTheCompartment) {
  const fs::path path = fs::temp_directory_path() / "nano_scene_bake_fin.obj";
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\nf 2 3 5\n";
  scene::CompartmentDescription c = tetrahedron(path);
  c.mesh.repair = true;
  try {
    scene_bake::load_compartment_mesh(c);
    ADD_FAILURE() << "repaired a fin";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_EQ(e.where(), "compartment 'tetra'");
    EXPECT_EQ(e.rule().rfind("cannot repair: 3 faces (triangles 0, 2, 4) share the edge", 0), 0u) << e.what();
  }
}

// A mesh that needs remeshing for its membrane (a tetrahedron's sharp creases) but has a hole is
// refused with every problem of its own listed, not only the first the remeshing would name.
TEST(CompartmentMesh, MeshToRemeshWithAHoleIsRefusedWithItsProblemsListed) {
  scene::CompartmentDescription c = tetrahedron(tetrahedron_file("nano_scene_bake_open_remesh.obj", true));
  c.mesh.diameter = 1000.0;
  // The point of the test: at that size it needs remeshing (else the chart stage refuses it alike).
  mesh::ProxyMesh sized = mesh::read_proxy_mesh(c.mesh.file);
  scene_bake::scale_mesh(sized, 1000.0 / mesh::largest_side(sized));
  ASSERT_TRUE(mesh::remesh_needed(sized, mesh::check_mesh(sized, {}), mesh::RemeshPolicy{}).has_value());
  try {
    scene_bake::load_compartment_mesh(c, 40.0);
    ADD_FAILURE() << "accepted an open mesh for a membrane";
  } catch (const InputError& e) {
    EXPECT_NE(e.file().find("nano_scene_bake_open_remesh.obj"), std::string::npos) << e.what();
    EXPECT_EQ(e.rule().rfind("mesh is not usable for compartment 'tetra':", 0), 0u) << e.what();
    EXPECT_NE(e.rule().find("border edge"), std::string::npos) << e.what();
  }
}

// "repair": the open tetrahedron is closed by one triangle, then charted; the report says so.
TEST(CompartmentMesh, RepairClosesTheHoleAndTheBakerChartsTheResult) {
  scene::CompartmentDescription c = tetrahedron(tetrahedron_file("nano_scene_bake_repair.obj", true));
  c.mesh.repair = true;
  c.mesh.volume = 1000.0;  // measured on the closed, repaired surface
  const scene_bake::CompartmentMesh m = scene_bake::load_compartment_mesh(c);
  ASSERT_TRUE(m.report.volume.has_value());
  EXPECT_NEAR(*m.report.volume, 1000.0, 1e-6);
  ASSERT_TRUE(m.repair.has_value());
  EXPECT_EQ(m.repair->holes_filled, 1u);
  EXPECT_EQ(m.repair->triangles_added, 1u);
  EXPECT_TRUE(m.report.usable());
  EXPECT_TRUE(m.report.closed);
  EXPECT_TRUE(m.charts.has_value());
}

// Units, then a target diameter (largest box side) or volume; the scale is reported.
TEST(CompartmentMesh, UnitsDiameterAndVolumeScaleTheMesh) {
  scene::CompartmentDescription c = tetrahedron(tetrahedron_file("nano_scene_bake_units.obj"));
  c.mesh.unit = 10.0;  // nm
  scene_bake::CompartmentMesh m = scene_bake::load_compartment_mesh(c);
  EXPECT_DOUBLE_EQ(m.scale, 10.0);
  double largest_x = 0;
  for (const glm::dvec3& p : m.mesh.positions) largest_x = std::max(largest_x, p.x);
  EXPECT_DOUBLE_EQ(largest_x, 10.0);
  c.mesh.diameter = 250.0;
  m = scene_bake::load_compartment_mesh(c);
  EXPECT_NEAR(m.scale, 250.0, 1e-9);
  double largest_z = 0;
  for (const glm::dvec3& p : m.mesh.positions) largest_z = std::max(largest_z, p.z);
  EXPECT_NEAR(largest_z, 250.0, 1e-9);
  c.mesh.diameter.reset();
  c.mesh.volume = 1000.0;  // (1/6)·s³ = 1000 → s = 6000^(1/3)
  m = scene_bake::load_compartment_mesh(c);
  EXPECT_NEAR(m.scale, std::cbrt(6000.0), 1e-9);
  ASSERT_TRUE(m.report.volume.has_value());
  EXPECT_NEAR(*m.report.volume, 1000.0, 1e-6);
  // A volume needs a closed, outward surface: inside out it encloses a negative volume.
  const fs::path inside_out = fs::temp_directory_path() / "nano_scene_bake_inside_out.obj";
  std::ofstream(inside_out) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\nf 2 4 3\nf 3 4 1\n";
  scene::CompartmentDescription reversed = tetrahedron(inside_out);
  reversed.mesh.volume = 1000.0;
  EXPECT_NE(load_error(reversed).find("closed, outward mesh"), std::string::npos) << load_error(reversed);
}

TEST(WangBake, PerTileAbundanceConvertsToSurfaceDensity) {
  // 2 copies on a 200 Å tile: 2 / (4e4 Å²) = 2 / 4e-4 µm² = 5000 per µm².
  EXPECT_DOUBLE_EQ(scene_bake::copies_per_um2_from_per_tile(2.0, 200.0), 5000.0);
}

TEST(WangBake, TileMoleculeKeepsAtomsRadiusAndUpAxis) {
  scene_bake::BakedMolecule m;
  m.name = "two";
  structure::Atom a, b;
  a.position = {1, 2, 3};
  a.radius = 1.5;
  b.position = {-1, 0, 0};
  b.radius = 1.7;
  m.atoms = {a, b};
  m.properties.bounding_radius = 5.25;
  m.up = {0, 1, 0};
  const tiles::MoleculeType t = scene_bake::to_tile_molecule(m);
  ASSERT_EQ(t.atoms.size(), 2u);
  EXPECT_EQ(t.atoms[0].centre, glm::vec3(1, 2, 3));
  EXPECT_FLOAT_EQ(t.atoms[1].radius, 1.7f);
  EXPECT_FLOAT_EQ(t.bounding_radius, 5.25f);
  EXPECT_EQ(t.up_axis, glm::vec3(0, 1, 0));
  EXPECT_EQ(t.name, "two");
}

// A small rigid "protein": eight atoms on a 6 Å cube, bounding radius √27 + 1.7.
scene_bake::BakedMolecule cube_molecule(const std::string& name) {
  scene_bake::BakedMolecule m;
  m.name = name;
  for (int i = 0; i < 8; ++i) {
    structure::Atom a;
    a.position = {i & 1 ? 3.0 : -3.0, i & 2 ? 3.0 : -3.0, i & 4 ? 3.0 : -3.0};
    a.radius = 1.7;
    m.atoms.push_back(a);
  }
  m.properties.bounding_radius = std::sqrt(27.0) + 1.7;
  return m;
}

TEST(WangBake, MembraneTilesReachTheDensityOrSayWhatTheSurfaceCosts) {
  const std::vector<scene_bake::BakedMolecule> library{cube_molecule("blob")};
  scene::MembraneDescription membrane;
  membrane.name = "m";
  membrane.tile_size = 60;
  membrane.proteins = {{{"blob", 0}, {scene::SurfaceAbundance::Unit::per_tile, 4.0}, 0.0}};
  const scene_bake::BakedWangSet flat = scene_bake::bake_membrane_tiles(membrane, library, nullptr, {}, 3);
  ASSERT_EQ(flat.set.densities.size(), 1u);
  EXPECT_EQ(flat.set.densities[0].name, "blob");
  EXPECT_NEAR(flat.set.densities[0].achieved, flat.set.densities[0].requested, 0.1 * flat.set.densities[0].requested);
  // Packed densely enough that a strongly tilted, stretched surface cannot hold it: the error names
  // the scene key of the amount and says what the meshes cost and what helps.
  membrane.proteins[0].abundance.value = 30.0;
  try {
    scene_bake::bake_membrane_tiles(membrane, library, nullptr, {0.5f, 0.01f, 0.4f, 50.f}, 3);
    ADD_FAILURE() << "an impossible density was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.where(), "membranes.m.proteins[0].copies_per_tile") << what;
    EXPECT_NE(what.find("best achieved"), std::string::npos) << what;
    EXPECT_NE(what.find("chart stretch 1.5"), std::string::npos) << what;
    EXPECT_NE(what.find("a finer mesh lowers the tilt"), std::string::npos) << what;
  }
}

TEST(WangBake, MembraneRecipeCoversTheUvSquareAndIsPeriodic) {
  tiles::WangSet set;
  set.dims = 2;
  set.colouring = tiles::make_complete_colouring(2, 2);
  const tiles::TilingRecipe r = scene_bake::membrane_recipe(set, 0.03, 5);
  EXPECT_EQ(r.size[0], 34);  // ceil(1 / 0.03)
  EXPECT_EQ(r.size[1], 34);
  EXPECT_TRUE(r.periodic);
  const tiles::TilingRecipe capped = scene_bake::membrane_recipe(set, 1e-5, 5);
  EXPECT_EQ(capped.size[0], scene_bake::kMaxRecipe2DCells);
}

TEST(WangBake, SolubleRecipeCoversSmallGridsAndRepeatsOnlyCompleteSets) {
  tiles::WangSet complete;
  complete.dims = 3;
  complete.colouring = tiles::make_complete_colouring(3, 2);
  const tiles::TilingRecipe small = scene_bake::soluble_recipe(complete, {5, 6, 7}, 1, "s");
  EXPECT_EQ(small.size, (std::array<int, 3>{5, 6, 7}));
  const tiles::TilingRecipe big = scene_bake::soluble_recipe(complete, {300, 300, 100}, 1, "s");
  EXPECT_EQ(big.size, (std::array<int, 3>{64, 64, 64}));
  EXPECT_TRUE(big.periodic);

  tiles::WangSet variants;
  variants.dims = 3;
  variants.colouring = tiles::make_variant_colouring(3, 2, 2, 9);
  EXPECT_EQ(scene_bake::soluble_recipe(variants, {10, 10, 10}, 1, "s").size, (std::array<int, 3>{10, 10, 10}));
  try {
    scene_bake::soluble_recipe(variants, {300, 300, 100}, 1, "cytoplasm");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("solubles.cytoplasm.cubes"), std::string::npos) << e.what();
  }
}

}  // namespace

#include "bake/scene_bake/membrane_bake.hpp"

namespace {

TEST(MembraneBake, StoredUvScaleReproducesTheTileUvSizeInFloat) {
  for (const float s : {1.04e-3f, 0.0123f, 3.3e-5f, 0.25f}) {
    const float k = nano::scene_bake::stored_uv_scale(200.f, s);
    EXPECT_EQ(200.f / k, s) << s;  // exactly what a shader computes from the package
  }
}

TEST(MembraneBake, EmptyShellsAreFlatAndSpanEachTriangleUvBox) {
  const nano::mesh::ProxyMesh sphere = nano::mesh::make_sphere_mesh(48, 10.0);
  const auto shells = nano::scene_bake::empty_shells(sphere);
  ASSERT_EQ(shells.size(), sphere.triangles.size());
  for (std::size_t t = 0; t < shells.size(); ++t) {
    EXPECT_EQ(shells[t].h_plus, 0.f);
    EXPECT_EQ(shells[t].side_offset, 0.f);
    for (int c = 0; c < 3; ++c) {
      const glm::vec2 uv(sphere.corner_uv(t, c));
      EXPECT_GE(uv.x, shells[t].uv_min_max.x);
      EXPECT_LE(uv.y, shells[t].uv_min_max.w);
    }
  }
}

}  // namespace
