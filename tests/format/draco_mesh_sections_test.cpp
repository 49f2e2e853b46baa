// Draco mesh sections (format 2.6): the grids, the canonical order, the writer's choice, the reader's
// decoding, and every way a hostile "draco_meshes" section or table can lie.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>

#include <glm/geometric.hpp>

#include "format/draco_mesh_sections.hpp"
#include "format/writer.hpp"
#include "tests/format/package_bytes.hpp"
#include "tests/format/sample_scene.hpp"

namespace nano::format {
namespace {

using glm::vec2;
using glm::vec4;
using test::broken_rule;
using test::entry_at;
using test::entry_index;
using test::get_le;
using test::put_le;
using test::resealed;

using test::grid_sphere;

gpu::Mesh record_of(const MeshArrays& m, std::uint32_t first_vertex = 0, std::uint32_t first_triangle = 0) {
  gpu::Mesh r{};
  r.first_vertex = first_vertex;
  r.vertex_count = std::uint32_t(m.positions.size());
  r.first_triangle = first_triangle;
  r.triangle_count = std::uint32_t(m.triangles.size());
  return r;
}

DracoEncoding encode(const MeshArrays& m) {
  const gpu::Mesh r = record_of(m);
  return encode_draco_meshes(std::span(&r, 1), m.positions, m.normals, m.uvs, m.triangles);
}

TEST(DracoGrids, OctahedralNormalsAreUnitAndCloseAndReachTheGrid) {
  std::mt19937 rng(7);
  std::normal_distribution<float> g;
  int fixed_in_one = 0;
  for (int i = 0; i < 20000; ++i) {
    const vec4 n = vec4(glm::normalize(glm::vec3(g(rng), g(rng), g(rng))), 0);
    const vec4 snapped = snap_normal_to_grid(n);
    EXPECT_NEAR(glm::length(glm::vec3(snapped)), 1.0f, 1e-6f);
    // 16-bit octahedral cells are under 1e-4 rad across.
    const glm::dvec3 before(n), after(snapped);
    EXPECT_LT(std::atan2(glm::length(glm::cross(before, after)), glm::dot(before, after)), 1e-4) << i;
    const auto [a, b] = encode_octahedral(snapped);
    const vec4 again = decode_octahedral(a, b);
    EXPECT_EQ(std::bit_cast<glm::uvec4>(again), std::bit_cast<glm::uvec4>(snapped)) << "normal " << i << " is off the grid";
    const auto [a0, b0] = encode_octahedral(n);
    fixed_in_one += std::bit_cast<glm::uvec4>(decode_octahedral(a0, b0)) == std::bit_cast<glm::uvec4>(snapped);
  }
  EXPECT_GT(fixed_in_one, 19000);  // one round nearly always suffices
  // The six axes and the fold's edges are exact.
  for (const vec4 axis : {vec4(1, 0, 0, 0), vec4(-1, 0, 0, 0), vec4(0, 1, 0, 0), vec4(0, -1, 0, 0), vec4(0, 0, 1, 0), vec4(0, 0, -1, 0)})
    EXPECT_EQ(std::bit_cast<glm::uvec4>(snap_normal_to_grid(axis)), std::bit_cast<glm::uvec4>(axis));
  EXPECT_EQ(encode_octahedral(vec4(0, 0, 0, 0)), std::make_pair(0, 0));  // no direction: never "on the grid"
}

TEST(DracoGrids, PowerOfTwoGridIsTheCoarsestStepHoldingEveryValue) {
  const auto grid = [](std::vector<float> v) { return power_of_two_grid(v); };
  EXPECT_EQ(grid({0.5f, 0.25f, 3.0f}), 0.25f);
  EXPECT_EQ(grid({3.0f, -6.0f}), 1.0f);
  EXPECT_EQ(grid({12.0f, 40.0f}), 4.0f);
  EXPECT_EQ(grid({0.0f, 0.0f}), 1.0f);
  EXPECT_EQ(grid({}), 1.0f);
  EXPECT_EQ(grid({0x1p-24f, 1.0f}), 0x1p-24f);
  EXPECT_EQ(grid({-0.0f}), std::nullopt);       // -0 would not come back as -0
  EXPECT_EQ(grid({std::nanf(""), 1.0f}), std::nullopt);
  EXPECT_EQ(grid({1e-9f, 1e8f}), std::nullopt);  // would need integers beyond 2^28
  EXPECT_EQ(grid({0.1f}), 0x1p-27f);             // 0.1f = 13421773 * 2^-27
  EXPECT_EQ(grid({0.1f, 100.0f}), std::nullopt);  // 100 / 2^-27 is beyond 2^28
}

TEST(DracoGrids, StoragePositionStepIsAThirtySecondOfAnAngstromUntilTheIntegersRunOut) {
  EXPECT_EQ(storage_position_step(100.0), 1.f / 32);
  EXPECT_EQ(storage_position_step(40000.0), 1.f / 32);  // a red blood cell
  const float big = storage_position_step(1e8);          // a 2 cm mesh
  EXPECT_GT(big, 1.f / 32);
  EXPECT_LE(1e8 / big, double(kMaxGridInteger));
  EXPECT_EQ(snap_to_step(-0.01, 1.f / 32), 0.0f);
  EXPECT_FALSE(std::signbit(snap_to_step(-0.01, 1.f / 32)));  // -0 made +0
  EXPECT_EQ(snap_to_step(1.02, 1.f / 32), 1.03125f);
}

TEST(DracoCanonicalOrder, AnyRenumberingGivesTheSameArrays) {
  const MeshArrays canonical = grid_sphere(6, 9, 100.f);
  EXPECT_TRUE(same_bits(canonical_mesh_order(canonical), canonical));  // idempotent
  std::mt19937 rng(3);
  for (int trial = 0; trial < 5; ++trial) {
    // Shuffle vertices, shuffle triangles, rotate each triangle's corners.
    std::vector<std::uint32_t> perm(canonical.positions.size());
    std::iota(perm.begin(), perm.end(), 0u);
    std::shuffle(perm.begin(), perm.end(), rng);
    MeshArrays shuffled;
    shuffled.positions.resize(perm.size());
    shuffled.normals.resize(perm.size());
    shuffled.uvs.resize(perm.size());
    for (std::size_t v = 0; v < perm.size(); ++v) {
      shuffled.positions[perm[v]] = canonical.positions[v];
      shuffled.normals[perm[v]] = canonical.normals[v];
      shuffled.uvs[perm[v]] = canonical.uvs[v];
    }
    for (const gpu::Triangle& t : canonical.triangles) {
      std::array<std::uint32_t, 3> c{perm[t.v0], perm[t.v1], perm[t.v2]};
      std::rotate(c.begin(), c.begin() + std::uniform_int_distribution<int>(0, 2)(rng), c.end());
      shuffled.triangles.push_back({c[0], c[1], c[2]});
    }
    std::shuffle(shuffled.triangles.begin(), shuffled.triangles.end(), rng);
    // And a duplicate vertex nobody can tell apart, plus one nobody uses.
    shuffled.positions.push_back(shuffled.positions[shuffled.triangles[0].v0]);
    shuffled.normals.push_back(shuffled.normals[shuffled.triangles[0].v0]);
    shuffled.uvs.push_back(shuffled.uvs[shuffled.triangles[0].v0]);
    shuffled.triangles[0].v0 = std::uint32_t(shuffled.positions.size() - 1);
    shuffled.positions.push_back(vec4(5, 5, 5, 0));
    shuffled.normals.push_back(vec4(0, 0, 1, 0));
    shuffled.uvs.push_back(vec2(0.5f));
    EXPECT_TRUE(same_bits(canonical_mesh_order(shuffled), canonical)) << "trial " << trial;
  }
  // Orientation is kept: a flipped triangle is a different mesh.
  MeshArrays flipped = canonical;
  std::swap(flipped.triangles[0].v1, flipped.triangles[0].v2);
  EXPECT_FALSE(same_bits(canonical_mesh_order(flipped), canonical));
  MeshArrays bad = canonical;
  bad.triangles[2].v1 = std::uint32_t(bad.positions.size());
  EXPECT_THROW(canonical_mesh_order(bad), std::invalid_argument);
}

TEST(DracoMeshSections, EncodingIsExactAndSmallerThanZstd) {
  const MeshArrays sphere = grid_sphere(24, 48, 900.f);
  const DracoEncoding draco = encode(sphere);
  ASSERT_TRUE(draco.why.empty()) << draco.why;
  const gpu::Mesh r = record_of(sphere);
  const MeshArrays decoded = decode_draco_meshes(draco.section, std::span(&r, 1), sphere.positions.size(), sphere.triangles.size());
  EXPECT_TRUE(same_bits(decoded, sphere));
  const std::uint64_t zstd = zstd_stored_size(std::as_bytes(std::span(sphere.positions))) +
                             zstd_stored_size(std::as_bytes(std::span(sphere.normals))) +
                             zstd_stored_size(std::as_bytes(std::span(sphere.uvs))) +
                             zstd_stored_size(std::as_bytes(std::span(sphere.triangles)));
  EXPECT_LT(draco.section.size() * 3 / 2, zstd) << "Draco " << draco.section.size() << " bytes, zstd " << zstd;
}

TEST(DracoMeshSections, TwoMeshesFollowEachOther) {
  const MeshArrays a = grid_sphere(5, 8, 50.f), b = grid_sphere(7, 11, 4000.f);
  MeshArrays both = a;
  both.positions.insert(both.positions.end(), b.positions.begin(), b.positions.end());
  both.normals.insert(both.normals.end(), b.normals.begin(), b.normals.end());
  both.uvs.insert(both.uvs.end(), b.uvs.begin(), b.uvs.end());
  both.triangles.insert(both.triangles.end(), b.triangles.begin(), b.triangles.end());
  const std::array<gpu::Mesh, 2> records = {record_of(a), record_of(b, std::uint32_t(a.positions.size()), std::uint32_t(a.triangles.size()))};
  const DracoEncoding draco = encode_draco_meshes(records, both.positions, both.normals, both.uvs, both.triangles);
  ASSERT_TRUE(draco.why.empty()) << draco.why;
  EXPECT_TRUE(same_bits(decode_draco_meshes(draco.section, records, 1u << 20, 1u << 20), both));
  // Each mesh's arrays come out of the sections by its record; a range past them is refused.
  EXPECT_TRUE(same_bits(mesh_arrays(records, 1, both.positions, both.normals, both.uvs, both.triangles), b));
  std::array<gpu::Mesh, 2> past = records;
  past[1].vertex_count += 1;
  EXPECT_THROW(mesh_arrays(past, 1, both.positions, both.normals, both.uvs, both.triangles), std::out_of_range);
  // Ranges that overlap or leave gaps are refused before anything is encoded.
  std::array<gpu::Mesh, 2> gap = records;
  gap[1].first_vertex += 1;
  EXPECT_NE(encode_draco_meshes(gap, both.positions, both.normals, both.uvs, both.triangles).why, "");
}

TEST(DracoMeshSections, MeshesOffTheGridsOrOrderAreLeftToZstdWithAReason) {
  const MeshArrays sphere = grid_sphere(6, 10, 100.f);
  MeshArrays off = sphere;
  off.positions[3].x += 1e-4f;  // no longer a multiple of any coarse step
  off = canonical_mesh_order(off);
  EXPECT_NE(encode(off).why.find("positions"), std::string::npos) << encode(off).why;
  MeshArrays tilted = sphere;
  tilted.normals[2] = glm::vec4(glm::normalize(glm::vec3(tilted.normals[2]) + glm::vec3(1e-3f)), 0);
  tilted = canonical_mesh_order(tilted);
  EXPECT_NE(encode(tilted).why.find("octahedral"), std::string::npos) << encode(tilted).why;
  MeshArrays shuffled = sphere;
  std::swap(shuffled.triangles[0], shuffled.triangles[1]);
  EXPECT_NE(encode(shuffled).why.find("canonical"), std::string::npos);
  MeshArrays w = sphere;
  w.positions[0].w = 1;
  w = canonical_mesh_order(w);
  EXPECT_NE(encode(w).why, "");
}

// The sample scene written with Draco mesh sections.
std::vector<std::byte> draco_package(Compression c = Compression::draco) {
  return build_package(test::sections_of(test::make_sample_scene(), c));
}

TEST(DracoPackage, EverySectionKindRoundTripsWithDracoMeshSections) {
  const test::SampleScene s = test::make_sample_scene();
  const Package p = Package::from_bytes(draco_package());
  EXPECT_EQ(p.entries().size(), std::size(kAllSectionKinds));
  for (const SectionKind k : kDracoCodedKinds) {
    ASSERT_TRUE(p.has(k));
    EXPECT_EQ(p.entry(k)->codec, static_cast<std::uint16_t>(Codec::draco));
    EXPECT_EQ(p.entry(k)->stored_size, 0u);
  }
  ASSERT_TRUE(p.has(SectionKind::draco_meshes));
  EXPECT_TRUE(p.entry(SectionKind::draco_meshes)->flags & kSectionRequired);
  const auto bytes_equal = [](auto records, const auto& expected) {
    return records.size() == expected.size() && std::memcmp(records.data(), expected.data(), records.size_bytes()) == 0;
  };
  EXPECT_TRUE(bytes_equal(p.records<SectionKind::vertex_positions>(), s.vertex_positions));
  EXPECT_TRUE(bytes_equal(p.records<SectionKind::vertex_normals>(), s.vertex_normals));
  EXPECT_TRUE(bytes_equal(p.records<SectionKind::vertex_uvs>(), s.vertex_uvs));
  EXPECT_TRUE(bytes_equal(p.records<SectionKind::triangles>(), s.triangles));
  EXPECT_NO_THROW(validate_semantics(p));
  // Where a decoded byte is, for error reports: in the decoded bytes.
  EXPECT_TRUE(p.locate(SectionKind::triangles, 12).decompressed);
}

TEST(DracoPackage, IfSmallerPicksWhicheverIsSmaller) {
  // The tetrahedron: four tiny sections that zstd leaves raw (208 bytes) against a Draco stream.
  const test::SampleScene s = test::make_sample_scene();
  const gpu::Mesh& r = s.meshes[0];
  const DracoEncoding draco = encode_draco_meshes(std::span(&r, 1), s.vertex_positions, s.vertex_normals, s.vertex_uvs, s.triangles);
  ASSERT_TRUE(draco.why.empty()) << draco.why;
  std::uint64_t zstd = 0;
  for (const SectionKind k : kDracoCodedKinds) zstd += Package::from_bytes(build(s, Compression::zstd_if_smaller)).entry(k)->stored_size;
  const Package p = Package::from_bytes(draco_package(Compression::draco_if_smaller));
  EXPECT_EQ(p.has(SectionKind::draco_meshes), draco.section.size() < zstd) << "Draco " << draco.section.size() << ", zstd " << zstd;

  // A mesh off the grids stays zstd under draco_if_smaller, and draco demanded says why.
  test::SampleScene off = s;
  off.vertex_normals[0] = vec4(-0.57735f, -0.57735f, -0.57735f, 0);
  const Package q = Package::from_bytes(build_package(test::sections_of(off, Compression::draco_if_smaller)));
  EXPECT_FALSE(q.has(SectionKind::draco_meshes));
  EXPECT_NE(q.entry(SectionKind::vertex_normals)->codec, static_cast<std::uint16_t>(Codec::draco));
  try {
    build_package(test::sections_of(off, Compression::draco));
    ADD_FAILURE() << "draco demanded for a mesh off the grid";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("octahedral"), std::string::npos) << e.what();
  }
  // Asking Draco for some mesh sections only is a caller's bug.
  std::vector<SectionSource> partial = test::sections_of(s, Compression::draco);
  for (SectionSource& src : partial)
    if (src.kind == static_cast<std::uint32_t>(SectionKind::vertex_uvs)) src.compression = Compression::none;
  EXPECT_THROW(build_package(partial), std::invalid_argument);
}

std::size_t draco_section_offset(std::span<const std::byte> b) {
  return get_le(b, entry_at(entry_index(b, SectionKind::draco_meshes)) + 8, 8);
}

TEST(DracoPackage, HostileTablesAndStreamsAreRefusedByName) {
  const std::vector<std::byte> good = draco_package();
  ASSERT_EQ(broken_rule(good), std::nullopt);
  const std::size_t streams = draco_section_offset(good);
  const std::size_t streams_size = get_le(good, entry_at(entry_index(good, SectionKind::draco_meshes)) + 16, 8);
  const auto expect = [](std::vector<std::byte> b, Rule rule, const char* what) {
    const auto broken = broken_rule(resealed(std::move(b)));
    ASSERT_TRUE(broken.has_value()) << what << ": accepted";
    EXPECT_EQ(*broken, rule) << what << ": " << rule_name(*broken);
  };
  {  // draco on a kind it does not serve
    auto b = good;
    put_le(b, entry_at(entry_index(b, SectionKind::atoms)) + 4, 2, 2);
    expect(b, Rule::mesh_codec, "atoms coded draco");
  }
  {  // three of four
    auto b = good;
    const std::size_t uv = entry_at(entry_index(b, SectionKind::vertex_uvs));
    put_le(b, uv + 4, 2, 0);   // codec none with no stored bytes: raw size disagrees
    put_le(b, uv + 40, 8, 0);
    expect(b, Rule::record_size, "uvs none");
  }
  {  // the streams section without the kind being decoded... because it is gone
    auto b = good;
    put_le(b, entry_at(entry_index(b, SectionKind::draco_meshes)), 4, 4711);  // an unknown (required) kind now
    expect(b, Rule::unknown_required_section, "draco_meshes renamed");
  }
  {  // stored bytes on a Draco-coded entry
    auto b = good;
    put_le(b, entry_at(entry_index(b, SectionKind::triangles)) + 16, 8, 4);
    put_le(b, entry_at(entry_index(b, SectionKind::triangles)) + 8, 8, streams);  // overlaps draco_meshes
    const auto rule = broken_rule(resealed(b));
    EXPECT_TRUE(rule == Rule::overlap || rule == Rule::mesh_codec);
  }
  {  // directory: count
    auto b = good;
    put_le(b, streams, 4, 2);
    expect(b, Rule::decompression, "two streams for one mesh");
  }
  {  // directory: reserved
    auto b = good;
    put_le(b, streams + 4, 4, 1);
    expect(b, Rule::decompression, "reserved word");
  }
  {  // directory: stream size past the end
    auto b = good;
    put_le(b, streams + 8 + 4, 4, streams_size);
    expect(b, Rule::decompression, "stream past the end");
  }
  {  // directory: a step that is no power of two (then the positions' floats would differ)
    auto b = good;
    put_le(b, streams + 8 + 8, 4, std::bit_cast<std::uint32_t>(3.0f));
    expect(b, Rule::decompression, "step 3");
  }
  {  // directory: another power of two: decodes, but to other floats than the table's checksum
    auto b = good;
    put_le(b, streams + 8 + 8, 4, std::bit_cast<std::uint32_t>(2.0f));
    expect(b, Rule::raw_checksum, "step 2");
  }
  {  // a stream cut short: the directory and section shrink with it
    auto b = good;
    const std::size_t cut = 8;
    put_le(b, streams + 8 + 4, 4, get_le(b, streams + 8 + 4, 4) - cut);
    const std::size_t entry = entry_at(entry_index(b, SectionKind::draco_meshes));
    put_le(b, entry + 16, 8, streams_size - cut);
    put_le(b, entry + 24, 8, streams_size - cut);
    std::fill(b.begin() + std::ptrdiff_t(streams + streams_size - cut), b.begin() + std::ptrdiff_t(streams + streams_size), std::byte{0});
    expect(b, Rule::decompression, "stream cut short");
  }
  {  // every byte of the stream flipped: refused by name, or (where Draco ignores the bit) the very same meshes
    const std::size_t first = streams + 8 + 16;
    int refused = 0;
    for (std::size_t at = first; at < streams + streams_size; ++at) {
      auto b = good;
      b[at] ^= std::byte{0x5a};
      const auto rule = broken_rule(resealed(b));
      if (!rule) continue;
      ++refused;
      EXPECT_TRUE(*rule == Rule::decompression || *rule == Rule::raw_checksum) << at - first << ": " << rule_name(*rule);
    }
    EXPECT_GT(refused, int(streams + streams_size - first) / 2);
  }
  {  // the meshes section claims another vertex count than the stream decodes to
    const test::SampleScene scene = test::make_sample_scene();
    std::vector<SectionSource> sections = test::sections_of(scene, Compression::draco);
    for (SectionSource& src : sections)
      if (src.kind == static_cast<std::uint32_t>(SectionKind::meshes)) src.compression = Compression::none;
    auto b = build_package(sections);
    const std::size_t meshes = get_le(b, entry_at(entry_index(b, SectionKind::meshes)) + 8, 8);
    put_le(b, meshes + 36, 4, 3);  // Mesh.vertex_count, byte 36
    expect(b, Rule::decompression, "vertex count 3");
  }
  {  // raw size in the table disagrees with what decodes
    auto b = good;
    const std::size_t pos = entry_at(entry_index(b, SectionKind::vertex_positions));
    put_le(b, pos + 24, 8, get_le(b, pos + 24, 8) + 16);
    expect(b, Rule::decompression, "raw size one vertex more");
  }
  {  // raw checksum
    auto b = good;
    const std::size_t n = entry_at(entry_index(b, SectionKind::vertex_normals));
    put_le(b, n + 40, 8, get_le(b, n + 40, 8) ^ 1);
    expect(b, Rule::raw_checksum, "normals' raw checksum");
  }
}

TEST(DracoPackage, AStreamsSectionWithoutDracoCodedSectionsIsRefused) {
  const test::SampleScene s = test::make_sample_scene();
  std::vector<SectionSource> sections = test::sections_of(s, Compression::none);
  const std::vector<std::byte> stray(64, std::byte{0});
  sections.push_back({static_cast<std::uint32_t>(SectionKind::draco_meshes), stray, Compression::none, 0});
  EXPECT_EQ(broken_rule(build_package(sections)), Rule::mesh_codec);
}

}  // namespace
}  // namespace nano::format
