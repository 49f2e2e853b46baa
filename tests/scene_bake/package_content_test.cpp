// The scene baker's package content: what it writes must pass the independent validator, and the
// records must say what was put in.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "bake/mesh/sphere_mesh.hpp"
#include "bake/scene_bake/package_content.hpp"
#include "bake/scene_bake/provenance.hpp"
#include "bake/tiles/wang_colouring.hpp"
#include "format/package.hpp"
#include "format/validator.hpp"

namespace {

using namespace nano;

scene_bake::BakedMolecule two_atom_molecule() {
  scene_bake::BakedMolecule m;
  m.name = "pair";
  m.source = "pair.pdb";
  structure::Atom a, b;
  a.position = {-1, 0, 0};
  a.radius = 1.5;
  a.chain = "A";
  a.residue_name = "GLY";
  a.residue_number = 7;
  a.atom_name = "CA";
  a.element = "C";
  b = a;
  b.position = {1, 0, 0};
  b.atom_name = "N";
  b.element = "N";
  m.atoms = {a, b};
  m.properties.spheres.min = {-2.5, -1.5, -1.5};
  m.properties.spheres.max = {2.5, 1.5, 1.5};
  m.properties.bounding_radius = 2.5;
  m.up = {0, 0, 1};
  m.linear_colour = {0.5, 0.25, 1.0};
  return m;
}

scene_bake::BakedWangSet one_square_set() {
  scene_bake::BakedWangSet s;
  s.set.dims = 2;
  s.set.edge = 100.f;
  s.set.colouring = tiles::make_complete_colouring(2, 1);
  tiles::WangTile tile;
  tile.instances.push_back({0, glm::vec3(10, 20, 0), glm::angleAxis(glm::radians(90.f), glm::vec3(0, 0, 1))});
  tile.atoms_min = {7.5, 17.5, -1.5};
  tile.atoms_max = {12.5, 22.5, 1.5};
  s.set.tiles.push_back(tile);
  s.molecule_of_type = {0};
  return s;
}

TEST(PackageContent, MoleculesTilesAndMeshPassTheValidatorWithTheirValues) {
  const std::vector<scene_bake::BakedMolecule> library{two_atom_molecule()};
  scene_bake::PackageContent content;
  EXPECT_EQ(content.add_molecule(library[0]), 0u);
  const scene_bake::TileRange range = content.add_wang_set(one_square_set(), library);
  EXPECT_EQ(range.first, 0u);
  EXPECT_EQ(range.count, 1u);
  tiles::TilingRecipe recipe;
  recipe.dims = 2;
  recipe.size = {2, 2, 1};
  recipe.cells = {0, 0, 0, 0};
  const std::uint32_t recipe_index = content.add_recipe(recipe, range);

  const mesh::ProxyMesh sphere = mesh::make_sphere_mesh(48, 50.0);
  const scene_bake::PackedMesh packed = scene_bake::pack_mesh(sphere);
  std::vector<gpu::TriangleShell> shells(packed.triangles.size());
  for (std::size_t t = 0; t < shells.size(); ++t) {
    const auto& tri = packed.triangles[t];
    glm::vec2 lo = glm::min(glm::min(packed.uvs[tri.v0], packed.uvs[tri.v1]), packed.uvs[tri.v2]);
    glm::vec2 hi = glm::max(glm::max(packed.uvs[tri.v0], packed.uvs[tri.v1]), packed.uvs[tri.v2]);
    shells[t].uv_min_max = glm::vec4(lo, hi);
    shells[t].h_plus = shells[t].h_minus = 3.f;
  }
  gpu::Compartment compartment{};
  compartment.mesh = content.add_mesh(packed, shells);
  compartment.membrane_first_tile = range.first;
  compartment.membrane_tile_count = range.count;
  compartment.membrane_recipe = recipe_index;
  compartment.soluble_recipe = gpu::NANO_NO_INDEX;
  compartment.replication_width = compartment.replication_height = 2;
  compartment.scales = glm::vec4(100.f, 100.f, 0.f, 0.f);
  std::tie(compartment.name_offset, compartment.name_length) = content.add_string("virion");
  content.compartments.push_back(compartment);
  gpu::CompartmentInstance instance{};
  instance.transform[0] = {1, 0, 0, 0};
  instance.transform[1] = {0, 1, 0, 0};
  instance.transform[2] = {0, 0, 1, 0};
  content.compartment_instances.push_back(instance);
  content.scene.camera_position = {0, 0, 500, 0.8f};
  content.scene.camera_up = {0, 1, 0, 0};
  content.provenance = "{}";

  const auto bytes = format::build_package(content.sections());
  const format::Package package = format::Package::from_bytes(bytes);
  EXPECT_NO_THROW(format::validate_semantics(package));

  const auto molecules = package.records<format::SectionKind::molecules>();
  ASSERT_EQ(molecules.size(), 1u);
  EXPECT_EQ(molecules[0].atom_count, 2u);
  EXPECT_FLOAT_EQ(molecules[0].aabb_min.w, 2.5f);
  const auto strings = package.records<format::SectionKind::strings>();
  EXPECT_EQ(std::string(strings.data() + molecules[0].name_offset, molecules[0].name_length), "pair");
  const auto info = package.records<format::SectionKind::atom_info>();
  ASSERT_EQ(info.size(), 2u);
  EXPECT_EQ(std::string(info[1].atom_name, 1), "N");
  EXPECT_EQ(info[0].residue_number, 7);
  // The 90° turn about z takes the pair from the x axis onto the y axis: the tile-space box is
  // (10 ± 1.5, 20 ± 2.5) by hand.
  const auto instances = package.records<format::SectionKind::instances>();
  ASSERT_EQ(instances.size(), 1u);
  EXPECT_NEAR(instances[0].aabb_min.x, 8.5, 1e-5);
  EXPECT_NEAR(instances[0].aabb_max.y, 22.5, 1e-5);
  EXPECT_NEAR(instances[0].rotation.w, std::sqrt(0.5), 1e-6);
  const auto tiles2d = package.records<format::SectionKind::tiles2d>();
  EXPECT_FLOAT_EQ(tiles2d[0].size.x, 100.f);
  EXPECT_EQ(package.records<format::SectionKind::triangles>().size(), sphere.triangles.size());
}

// The level of detail: each molecule type's beads follow its atoms, report absolute atom indices
// inside the type's own range, hold every atom sphere (the baker's double beads widened for the
// float centre) and pass the validator.
TEST(PackageContent, BeadsArePerTypeRangesOverAbsoluteAtoms) {
  scene_bake::BakedMolecule second = two_atom_molecule();
  second.atoms[1].residue_number = 8;  // two residues: two beads
  const std::vector<scene_bake::BakedMolecule> library{two_atom_molecule(), second};
  scene_bake::PackageContent content;
  content.add_molecule(library[0]);
  content.add_molecule(library[1]);
  ASSERT_EQ(content.bead_ranges.size(), 2u);
  EXPECT_EQ(content.bead_ranges[0].first, 0u);
  EXPECT_EQ(content.bead_ranges[0].count, 1u);
  EXPECT_EQ(content.bead_ranges[1].first, 1u);
  EXPECT_EQ(content.bead_ranges[1].count, 2u);
  ASSERT_EQ(content.beads.size(), 3u);
  // One residue: the bead about the pair's centre (0, 0, 0), radius 1 + 1.5, reporting its first atom.
  EXPECT_EQ(content.beads[0].centre_radius, glm::vec4(0, 0, 0, 2.501f));
  EXPECT_EQ(content.beads[0].atom, 0u);
  EXPECT_EQ(content.beads[0].atom_count, 2u);
  // The second type's atoms are atoms 2 and 3 of the package, a bead each.
  EXPECT_EQ(content.beads[1].atom, 2u);
  EXPECT_EQ(content.beads[2].atom, 3u);
  EXPECT_EQ(content.beads[2].centre_radius, glm::vec4(1, 0, 0, 1.501f));
  content.scene.camera_position = {0, 0, 500, 0.8f};
  content.scene.camera_up = {0, 1, 0, 0};
  const auto bytes = format::build_package(content.sections());
  const format::Package package = format::Package::from_bytes(bytes);
  EXPECT_NO_THROW(format::validate_semantics(package));
  EXPECT_EQ(package.records<format::SectionKind::beads>().size(), 3u);
  EXPECT_EQ(package.records<format::SectionKind::bead_ranges>().size(), 2u);
}

// Dropped membrane copies: one range per triangle of every mesh added, the keys in order, the
// sections written (required: a 2.1 reader must refuse them) only when a copy is dropped at all,
// and out-of-order keys refused.
TEST(PackageContent, DroppedCopiesArePerTriangleRangesWrittenOnlyWhenAny) {
  const scene_bake::PackedMesh packed = scene_bake::pack_mesh(mesh::make_sphere_mesh(48, 50.0));
  const std::vector<gpu::TriangleShell> shells(packed.triangles.size());
  scene_bake::PackageContent none;
  none.add_mesh(packed, shells);
  EXPECT_EQ(none.triangle_drops.size(), packed.triangles.size());
  EXPECT_TRUE(none.dropped_copies.empty());
  for (const auto& s : none.sections())
    EXPECT_NE(s.kind, std::uint32_t(format::SectionKind::triangle_drops)) << "no drop sections without a drop";

  std::vector<std::vector<std::uint32_t>> dropped(packed.triangles.size());
  dropped[1] = {3, (2u << 16) | 5u};
  dropped[7] = {1};
  scene_bake::PackageContent content;
  content.add_mesh(packed, shells);  // a first mesh without drops shifts nothing
  content.add_mesh(packed, shells, dropped);
  const std::size_t second = packed.triangles.size();
  EXPECT_EQ(content.dropped_copies, (std::vector<std::uint32_t>{3, (2u << 16) | 5u, 1}));
  EXPECT_EQ(content.triangle_drops[second + 1].first, 0u);
  EXPECT_EQ(content.triangle_drops[second + 1].count, 2u);
  EXPECT_EQ(content.triangle_drops[second + 7].first, 2u);
  EXPECT_EQ(content.triangle_drops[second + 7].count, 1u);
  EXPECT_EQ(content.triangle_drops[second + 8].first, 3u);
  EXPECT_EQ(content.triangle_drops[second + 8].count, 0u);
  int required = 0;
  for (const auto& s : content.sections())
    if (s.kind == std::uint32_t(format::SectionKind::triangle_drops) || s.kind == std::uint32_t(format::SectionKind::dropped_copies))
      required += (s.flags & format::kSectionRequired) != 0;
  EXPECT_EQ(required, 2);
  dropped[1] = {5, 3};
  const std::size_t meshes = content.meshes.size();
  EXPECT_THROW(content.add_mesh(packed, shells, dropped), std::invalid_argument);
  EXPECT_EQ(content.meshes.size(), meshes);
  EXPECT_EQ(content.triangle_drops.size(), 2 * packed.triangles.size()) << "a refused mesh adds nothing";
  dropped[1] = {3, 3};
  EXPECT_THROW(content.add_mesh(packed, shells, dropped), std::invalid_argument);
}

TEST(PackageContent, RecipesStoreAbsoluteTileIndices) {
  scene_bake::PackageContent content;
  tiles::TilingRecipe recipe;
  recipe.dims = 3;
  recipe.size = {1, 1, 2};
  recipe.cells = {0, 1};
  content.add_recipe(recipe, scene_bake::TileRange{5, 2});
  EXPECT_EQ(content.recipe_indices, (std::vector<std::uint32_t>{5, 6}));
  EXPECT_EQ(content.recipes[0].dims.w, gpu::NANO_RECIPE_3D);
}

TEST(PackageContent, KeepMasksArePaddedToTheLargestCube) {
  grid::KeepMasks masks;
  masks.boundary_boxes = {3, 9};
  masks.word_offsets = {0, 1, 2};
  masks.words = {0x5u, 0x1u};
  scene_bake::PackageContent content;
  const auto [first, count] = content.add_keep_masks(masks, 40);  // 40 molecules: 2 words per box
  EXPECT_EQ(first, 0u);
  EXPECT_EQ(count, 2u);
  ASSERT_EQ(content.boundary_boxes.size(), 2u);
  EXPECT_EQ(content.boundary_boxes[1].box, 9u);
  EXPECT_EQ(content.boundary_boxes[1].first_word, 2u);
  EXPECT_EQ(content.mask_words, (std::vector<std::uint32_t>{0x5u, 0u, 0x1u, 0u}));
}

TEST(Provenance, HashesFilesAndNamesThemRelativeToTheScene) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "nano_provenance_test";
  fs::create_directories(dir / "structures");
  std::ofstream(dir / "scene.json") << "{}";
  std::ofstream(dir / "structures" / "a.pdb") << "ATOM";
  std::ofstream(dir / "structures" / "b.pdb") << "ATOX";
  EXPECT_EQ(scene_bake::file_hash(dir / "structures" / "a.pdb"), scene_bake::file_hash(dir / "structures" / "a.pdb"));
  EXPECT_NE(scene_bake::file_hash(dir / "structures" / "a.pdb"), scene_bake::file_hash(dir / "structures" / "b.pdb"));
  EXPECT_EQ(scene_bake::file_hash(dir / "structures" / "a.pdb").size(), 16u);
  EXPECT_THROW(scene_bake::file_hash(dir / "missing.pdb"), nano::InputError);

  scene::SceneDescription s;
  s.source = dir / "scene.json";
  scene::MoleculeDescription m;
  m.name = "a";
  m.file = dir / "structures" / "a.pdb";
  s.molecules.push_back(m);
  const std::string json = scene_bake::provenance_json(s, 42);
  EXPECT_NE(json.find("\"structures/a.pdb\""), std::string::npos) << json;
  EXPECT_EQ(json.find(dir.string()), std::string::npos) << "no absolute paths: " << json;
  EXPECT_NE(json.find("\"seed\": 42"), std::string::npos) << json;
}

}  // namespace
