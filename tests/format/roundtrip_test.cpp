// Every section kind written and read back, compared field by field against the written values.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <tuple>
#include <zstd.h>

#include "format/package.hpp"
#include "format/validator.hpp"
#include "tests/format/sample_scene.hpp"

namespace nano::format::test {
namespace {

auto fields(const gpu::MoleculeType& m) {
  return std::tie(m.aabb_min, m.aabb_max, m.up_axis, m.colour, m.first_atom, m.atom_count, m.name_offset, m.name_length,
                  m.source_offset, m.source_length, m.reserved0, m.reserved1);
}
auto fields(const gpu::Atom& a) { return std::tie(a.centre_radius); }
auto fields(const AtomInfo& a) {
  return std::make_tuple(std::string(a.chain, 4), std::string(a.residue_name, 8), std::string(a.atom_name, 4),
                         std::string(a.element, 2), a.insertion_code, a.alt_location, a.residue_number);
}
auto fields(const gpu::Tile2D& t) {
  return std::tie(t.edge_colours, t.size, t.first_instance, t.instance_count, t.reserved0, t.reserved1);
}
auto fields(const gpu::Tile3D& t) {
  return std::tie(t.face_colours_xy, t.face_colours_z, t.size, t.first_instance, t.instance_count, t.reserved0, t.reserved1);
}
auto fields(const gpu::MoleculeInstance& m) {
  return std::tie(m.rotation, m.position, m.aabb_min, m.aabb_max, m.molecule_type, m.flags, m.reserved1, m.reserved2);
}
auto fields(const gpu::Recipe& r) { return std::tie(r.dims, r.first_index, r.index_count, r.reserved0, r.reserved1); }
auto fields(const gpu::Mesh& m) {
  return std::tie(m.aabb_min, m.aabb_max, m.first_vertex, m.vertex_count, m.first_triangle, m.triangle_count);
}
auto fields(const gpu::Triangle& t) { return std::tie(t.v0, t.v1, t.v2); }
auto fields(const gpu::TriangleShell& s) { return std::tie(s.uv_min_max, s.h_plus, s.h_minus, s.side_offset, s.seam_edges); }
auto fields(const gpu::Compartment& c) {
  return std::tie(c.grid_min, c.grid_dims, c.scales, c.mesh, c.membrane_first_tile, c.membrane_tile_count,
                  c.membrane_recipe, c.soluble_first_tile, c.soluble_tile_count, c.soluble_recipe, c.replication_width,
                  c.replication_height, c.name_offset, c.name_length, c.reserved0, c.core_masks);
}
auto fields(const gpu::BoundaryBox& b) { return std::tie(b.box, b.first_word); }
auto fields(const gpu::TriangleDrops& d) { return std::tie(d.first, d.count); }
auto fields(const gpu::Bead& b) { return std::tie(b.centre_radius, b.atom, b.atom_count, b.reserved0, b.reserved1); }
auto fields(const gpu::BeadRange& r) { return std::tie(r.first, r.count); }
auto fields(const gpu::Medium& m) { return std::tie(m.region_min, m.region_max, m.boxes, m.tiles); }
auto fields(const gpu::ExclusionField& f) { return std::tie(f.origin, f.dims, f.limits); }
auto fields(const gpu::SceneSettings& s) {
  return std::tie(s.camera_position, s.camera_look_at, s.camera_up, s.effect_flags, s.reserved0, s.reserved1, s.reserved2);
}
auto fields(const gpu::CompartmentInstance& c) {
  return std::tie(c.transform[0], c.transform[1], c.transform[2], c.compartment, c.reserved0, c.reserved1, c.reserved2);
}
template <class T> requires std::is_arithmetic_v<T> auto fields(const T& v) { return std::tie(v); }
auto fields(const glm::vec4& v) { return std::tie(v); }
auto fields(const glm::vec2& v) { return std::tie(v); }

template <SectionKind K, class V> void expect_section(const Package& p, const V& written) {
  SCOPED_TRACE(section_kind_name(K));
  ASSERT_TRUE(p.has(K));
  const std::span<const record_t<K>> read = p.records<K>();
  ASSERT_EQ(read.size(), written.size());
  EXPECT_EQ(p.record_count(K), written.size());
  for (std::size_t i = 0; i < read.size(); ++i) EXPECT_TRUE(fields(read[i]) == fields(written[i])) << "record " << i;
}

void expect_scene(const Package& p, const SampleScene& s) {
  using K = SectionKind;
  expect_section<K::strings>(p, s.strings);
  expect_section<K::molecules>(p, s.molecules);
  expect_section<K::atoms>(p, s.atoms);
  expect_section<K::atom_info>(p, s.atom_info);
  expect_section<K::tiles2d>(p, s.tiles2d);
  expect_section<K::tiles3d>(p, s.tiles3d);
  expect_section<K::instances>(p, s.instances);
  expect_section<K::recipes>(p, s.recipes);
  expect_section<K::recipe_indices>(p, s.recipe_indices);
  expect_section<K::meshes>(p, s.meshes);
  expect_section<K::vertex_positions>(p, s.vertex_positions);
  expect_section<K::vertex_normals>(p, s.vertex_normals);
  expect_section<K::vertex_uvs>(p, s.vertex_uvs);
  expect_section<K::triangles>(p, s.triangles);
  expect_section<K::triangle_shells>(p, s.triangle_shells);
  expect_section<K::compartments>(p, s.compartments);
  expect_section<K::occupancy>(p, s.occupancy);
  expect_section<K::scene>(p, s.scene);
  expect_section<K::compartment_instances>(p, s.compartment_instances);
  expect_section<K::provenance>(p, s.provenance);
  expect_section<K::boundary_boxes>(p, s.boundary_boxes);
  expect_section<K::mask_words>(p, s.mask_words);
  expect_section<K::triangle_drops>(p, s.triangle_drops);
  expect_section<K::dropped_copies>(p, s.dropped_copies);
  expect_section<K::beads>(p, s.beads);
  expect_section<K::bead_ranges>(p, s.bead_ranges);
  expect_section<K::medium>(p, s.medium);
  expect_section<K::exclusion_fields>(p, s.exclusion_fields);
  expect_section<K::exclusion_values>(p, s.exclusion_values);
}

TEST(RoundTrip, EverySectionKindUncompressed) {
  const SampleScene s = make_sample_scene();
  const Package p = Package::from_bytes(build(s, Compression::none));
  // All but draco_meshes, which exists only when the mesh sections are Draco-coded (draco_mesh_sections_test).
  EXPECT_EQ(p.entries().size(), std::size(kAllSectionKinds) - 1);
  EXPECT_FALSE(p.has(SectionKind::draco_meshes));
  for (const SectionEntry& e : p.entries()) EXPECT_EQ(e.codec, static_cast<std::uint16_t>(Codec::none));
  expect_scene(p, s);
  EXPECT_NO_THROW(validate_semantics(p));
}

TEST(RoundTrip, EverySectionKindWithZstdWherePays) {
  const SampleScene s = make_sample_scene();
  const Package p = Package::from_bytes(build(s, Compression::zstd_if_smaller));
  expect_scene(p, s);
  EXPECT_NO_THROW(validate_semantics(p));
  // 512 mostly-zero occupancy bytes shrink; 28 bytes of unrepeated text cannot pay for a frame header.
  EXPECT_EQ(p.entry(SectionKind::occupancy)->codec, static_cast<std::uint16_t>(Codec::zstd));
  EXPECT_LT(p.entry(SectionKind::occupancy)->stored_size, 512u);
  EXPECT_EQ(p.entry(SectionKind::strings)->codec, static_cast<std::uint16_t>(Codec::none));
  EXPECT_EQ(p.entry(SectionKind::strings)->stored_size, 28u);
}

TEST(RoundTrip, WrittenZstdSectionIsAStandardFrame) {
  const SampleScene s = make_sample_scene();
  const std::vector<std::byte> bytes = build(s);
  const Package p = Package::from_bytes(bytes);
  const SectionEntry& e = *p.entry(SectionKind::occupancy);
  // Oracle: libzstd's one-shot decoder on the stored bytes.
  std::vector<std::uint8_t> out(e.raw_size);
  const std::size_t n = ZSTD_decompress(out.data(), out.size(), bytes.data() + e.offset, e.stored_size);
  ASSERT_FALSE(ZSTD_isError(n));
  EXPECT_EQ(out, s.occupancy);
}

TEST(RoundTrip, SectionsAreAlignedAndUncompressedOnesReadInPlace) {
  const SampleScene s = make_sample_scene();
  const std::filesystem::path path = std::filesystem::path(::testing::TempDir()) / "roundtrip_inplace.nup";
  write_package(path, sections_of(s, Compression::none));
  const Package p = Package::open(path);
  EXPECT_EQ(p.file_size(), std::filesystem::file_size(path));
  const std::byte* base = p.raw_bytes(SectionKind::strings).data() - p.entry(SectionKind::strings)->offset;
  for (const SectionEntry& e : p.entries()) {
    EXPECT_EQ(e.offset % 256, 0u);
    const auto raw = p.raw_bytes(static_cast<SectionKind>(e.kind));
    EXPECT_EQ(raw.data(), base + e.offset) << section_kind_name(e.kind) << " is not a view into the map";
  }
  // The whole file is the page-aligned mapping the sections point into; a copy is not a mapping.
  EXPECT_TRUE(p.memory_mapped());
  EXPECT_EQ(p.file_bytes().data(), base);
  EXPECT_EQ(p.file_bytes().size(), p.file_size());
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p.file_bytes().data()) % 4096, 0u);
  const Package copy = Package::from_bytes(build(s, Compression::none));
  EXPECT_FALSE(copy.memory_mapped());
  EXPECT_EQ(copy.file_bytes().size(), p.file_size());
  expect_scene(p, s);
  std::filesystem::remove(path);
}

TEST(RoundTrip, OpenFromFileMatchesFromBytes) {
  const SampleScene s = make_sample_scene();
  const std::filesystem::path path = std::filesystem::path(::testing::TempDir()) / "roundtrip_file.nup";
  write_package(path, sections_of(s, Compression::zstd_if_smaller));
  std::ifstream in(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(std::as_bytes(std::span(bytes)).size(), build(s).size());
  EXPECT_TRUE(std::equal(bytes.begin(), bytes.end(), reinterpret_cast<const char*>(build(s).data())));
  const Package p = open_validated(path);
  expect_scene(p, s);
  std::filesystem::remove(path);
}

TEST(RoundTrip, EmptyPackageAndEmptySection) {
  const Package empty = Package::from_bytes(build_package({}));
  EXPECT_EQ(empty.entries().size(), 0u);
  EXPECT_EQ(empty.file_size(), kHeaderSize);
  EXPECT_FALSE(empty.has(SectionKind::atoms));
  EXPECT_TRUE(empty.records<SectionKind::atoms>().empty());
  EXPECT_NO_THROW(validate_semantics(empty));

  const std::vector<gpu::Atom> none;
  const SectionSource src = section_source(SectionKind::atoms, std::span<const gpu::Atom>(none));
  const Package p = Package::from_bytes(build_package(std::span(&src, 1)));
  EXPECT_TRUE(p.has(SectionKind::atoms));
  EXPECT_EQ(p.record_count(SectionKind::atoms), 0u);
}

TEST(Writer, RefusesDuplicateKindsAndPartialRecords) {
  const std::vector<gpu::Atom> atoms(2);
  const SectionSource twice[] = {section_source(SectionKind::atoms, std::span<const gpu::Atom>(atoms)),
                                 section_source(SectionKind::atoms, std::span<const gpu::Atom>(atoms))};
  EXPECT_THROW(build_package(twice), std::invalid_argument);
  const std::vector<std::byte> odd(17);
  const SectionSource partial[] = {{static_cast<std::uint32_t>(SectionKind::atoms), odd, Compression::none, 0}};
  EXPECT_THROW(build_package(partial), std::invalid_argument);
}

TEST(Writer, WritePackageLeavesNoTemporaryFile) {
  const SampleScene s = make_sample_scene();
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "nup_atomic";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  write_package(dir / "a.nup", sections_of(s, Compression::none));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);
  std::filesystem::remove_all(dir);
}

TEST(SectionKinds, NamesRoundTripAndRecordSizes) {
  for (SectionKind k : kAllSectionKinds) {
    EXPECT_TRUE(is_known_section_kind(static_cast<std::uint32_t>(k)));
    EXPECT_EQ(section_kind_from_name(section_kind_name(k)), k);
  }
  EXPECT_FALSE(is_known_section_kind(0));
  EXPECT_FALSE(is_known_section_kind(34));
  EXPECT_EQ(record_size(SectionKind::medium), 64u);
  EXPECT_EQ(record_size(SectionKind::exclusion_fields), 48u);
  EXPECT_EQ(record_size(SectionKind::exclusion_values), 4u);
  EXPECT_EQ(record_size(SectionKind::draco_meshes), 1u);
  EXPECT_EQ(record_size(SectionKind::triangle_drops), 8u);
  EXPECT_EQ(record_size(SectionKind::dropped_copies), 4u);
  EXPECT_EQ(record_size(SectionKind::beads), 32u);
  EXPECT_EQ(record_size(SectionKind::bead_ranges), 8u);
  EXPECT_EQ(record_size(SectionKind::effects), 256u);
  EXPECT_EQ(record_size(SectionKind::keyframes), 64u);
  EXPECT_EQ(section_kind_name(4711u), "kind 4711");
  EXPECT_EQ(section_kind_from_name("nonsense"), std::nullopt);
  EXPECT_EQ(record_size(SectionKind::molecules), 96u);
  EXPECT_EQ(record_size(SectionKind::atoms), 16u);
  EXPECT_EQ(record_size(SectionKind::atom_info), 24u);
  EXPECT_EQ(record_size(SectionKind::triangles), 12u);
  EXPECT_EQ(record_size(SectionKind::vertex_uvs), 8u);
  EXPECT_EQ(record_size(SectionKind::occupancy), 1u);
  EXPECT_EQ(record_size(SectionKind::provenance), 1u);
  EXPECT_EQ(record_size(SectionKind::compartments), 112u);
  EXPECT_EQ(record_size(SectionKind::boundary_boxes), 8u);
  EXPECT_EQ(record_size(SectionKind::mask_words), 4u);
}

}  // namespace
}  // namespace nano::format::test
