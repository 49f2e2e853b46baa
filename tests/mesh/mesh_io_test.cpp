// Loading OBJ, PLY, OFF, STL and Draco, the OBJ writer, normals, and bad input (each format's
// variants and hostile files: mesh_formats_test.cpp).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <set>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "bake/mesh/draco_codec.hpp"
#include "bake/mesh/mesh_reader.hpp"
#include "bake/mesh/obj_writer.hpp"
#include "bake/mesh/sphere_mesh.hpp"
#include "bake/mesh/vertex_normals.hpp"
#include "common/error.hpp"
#include "tests/mesh/test_obj.hpp"

namespace nano::mesh {
namespace {

using testing::expect_input_error;
using testing::TempDir;

TEST(MeshReader, ObjKeepsPerCornerUvsAndSeams) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write("octa.obj", testing::octahedron));
  ASSERT_EQ(mesh.triangles.size(), 8u);
  EXPECT_EQ(mesh.positions.size(), 6u);
  ASSERT_TRUE(mesh.has_uvs());
  // Face 4 is "2/2 1/1 6/6", face 7 is "1/1 4/4 6/9": vertex 6 (−Z) has different UVs in each.
  EXPECT_EQ(mesh.corner_position(4, 2), glm::dvec3(0, 0, -1));
  EXPECT_EQ(mesh.corner_uv(4, 2), glm::dvec2(1, 1));
  EXPECT_EQ(mesh.corner_uv(7, 2), glm::dvec2(1, 0));
  EXPECT_EQ(mesh.corner_uv(0, 1), glm::dvec2(0.5, 1));
  // No normals in the file: computed. At +Z (a vertex with four symmetric faces) the
  // angle-weighted normal is exactly up.
  ASSERT_TRUE(mesh.has_normals());
  EXPECT_NEAR(glm::length(mesh.corner_normal(0, 2) - glm::dvec3(0, 0, 1)), 0.0, 1e-12);
}

// A square's diagonals tie: the fan's 0–2 one is kept (mesh_formats_test.cpp has the shorter-diagonal cases).
TEST(MeshReader, PolygonsAreFanTriangulated) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(
      dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n"));
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangles[0], (Triangle{0, 1, 2}));
  EXPECT_EQ(mesh.triangles[1], (Triangle{0, 2, 3}));
  EXPECT_EQ(mesh.corner_uv(1, 2), glm::dvec2(0, 1));
}

TEST(MeshReader, ObjNormalsPerCornerAreKept) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write(
      "n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nvn 1 0 0\nvn 0 0 2\n"
               "f 1//1 2//1 3//1\nf 1//2 4//2 2//3\n"));
  ASSERT_TRUE(mesh.has_normals());
  EXPECT_FALSE(mesh.has_uvs());
  EXPECT_EQ(mesh.corner_normal(0, 0), glm::dvec3(0, 0, 1));
  EXPECT_EQ(mesh.corner_normal(1, 0), glm::dvec3(1, 0, 0));  // same vertex, another normal
  EXPECT_EQ(mesh.corner_normal(1, 2), glm::dvec3(0, 0, 1));  // normalised on load
}

TEST(MeshReader, PlyWithPerVertexUvs) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write("t.ply",
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property float u\nproperty float v\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n1 1 0 1 1\n3 0 1 2\n3 1 3 2\n"));
  ASSERT_EQ(mesh.triangles.size(), 2u);
  ASSERT_TRUE(mesh.has_uvs());
  EXPECT_EQ(mesh.corner_uv(1, 1), glm::dvec2(1, 1));
  EXPECT_EQ(mesh.corner_position(1, 1), glm::dvec3(1, 1, 0));
}

TEST(MeshReader, OffWithoutUvsLoadsWithoutUvs) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write("t.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_FALSE(mesh.has_uvs());
  EXPECT_NEAR(glm::length(mesh.normals.at(0) - glm::dvec3(0, 0, 1)), 0.0, 1e-12);
}

TEST(MeshReader, CoincidentVerticesAreWelded) {
  // Two triangles that share an edge through duplicated vertices (as PLY exporters write seams).
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write("w.obj",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 4 6 5\n"));
  EXPECT_EQ(mesh.positions.size(), 4u);
  EXPECT_EQ(mesh.triangles[1], (Triangle{1, 3, 2}));
}

TEST(MeshReader, BadInputNamesFileAndRule) {
  TempDir dir;
  expect_input_error(dir.path() / "missing.obj", "", "no such file");
  expect_input_error(dir.write("garbage.obj", "this is not\n\x01\x02 a mesh at all\n"), "", "no faces");
  expect_input_error(dir.write("empty.obj", ""), "", "no faces");
  expect_input_error(dir.write("points.obj", "v 0 0 0\nv 1 0 0\n"), "", "no faces");
  expect_input_error(dir.write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n"), "line 5, face 1",
                     "does not exist");
  expect_input_error(dir.write("repeat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 3\nf 2 2 3\n"),
                     "line 6, face 2", "repeated vertex");
  expect_input_error(dir.write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"), "line 2, vertex 1", "finite");
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float coordinates[9] = {0, 0, 0, std::nanf(""), 0, 0, 0, 1, 0};
  ply.append(reinterpret_cast<const char*>(coordinates), sizeof coordinates);
  const unsigned char count = 3;
  const std::int32_t indices[3] = {0, 1, 2};
  ply.append(reinterpret_cast<const char*>(&count), 1);
  ply.append(reinterpret_cast<const char*>(indices), sizeof indices);
  expect_input_error(dir.write("nan.ply", ply), "vertex 1", "finite");
  expect_input_error(dir.write("mesh.stl", "solid x\nendsolid x\n"), "", "");
  expect_input_error(dir.write("mesh.3ds", "MM\n"), "", "unsupported mesh format");
  expect_input_error(dir.write("garbage.drc", "DRACO but not really a Draco file at all"), "", "Draco");
  expect_input_error(dir.write("empty.drc", ""), "", "Draco");
  expect_input_error(dir.write("bad.ply", "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n"), "line 3",
                     "no x, y and z");
}

// The octahedron as ASCII STL (facets with their own corners, no UVs) reads as the OBJ does:
// corners welded back to 6 vertices, the same 8 triangles.
TEST(MeshReader, StlReadsAsTheObj) {
  TempDir dir;
  const ProxyMesh obj = read_proxy_mesh(dir.write("octa.obj", testing::octahedron));
  std::string stl = "solid octahedron\n";
  for (std::size_t t = 0; t < obj.triangles.size(); ++t) {
    stl += "facet normal 0 0 0\nouter loop\n";
    for (int c = 0; c < 3; ++c) {
      const glm::dvec3 p = obj.corner_position(t, c);
      stl += "vertex " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    }
    stl += "endloop\nendfacet\n";
  }
  stl += "endsolid octahedron\n";
  const ProxyMesh read = read_proxy_mesh(dir.write("octa.stl", stl));
  ASSERT_EQ(read.triangles.size(), obj.triangles.size());
  EXPECT_EQ(read.positions.size(), obj.positions.size());
  EXPECT_FALSE(read.has_uvs());
  for (std::size_t t = 0; t < obj.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(glm::length(read.corner_position(t, c) - obj.corner_position(t, c)), 0.0, 1e-6);
}

// Draco round trip: the mesh read back from a .drc equals the OBJ read of the same mesh
// within half a quantisation step (Draco quantises over the bounding box's largest side), with the
// same triangles (Draco may reorder them: compared as sets of welded positions).
TEST(MeshReader, DracoRoundTripWithinQuantisation) {
  TempDir dir;
  const auto obj_file = dir.path() / "sphere.obj";
  write_obj(obj_file, make_sphere_mesh(432, 500.0));
  const ProxyMesh original = read_proxy_mesh(obj_file);
  for (const int bits : {11, 16}) {
    SCOPED_TRACE(bits);
    const std::vector<std::byte> bytes = encode_draco_mesh(original, {.position_bits = bits, .uv_bits = bits, .normal_bits = 10});
    const auto drc = dir.path() / ("sphere" + std::to_string(bits) + ".drc");
    std::ofstream(drc, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    const ProxyMesh decoded = read_proxy_mesh(drc);
    ASSERT_EQ(decoded.triangles.size(), original.triangles.size());
    ASSERT_EQ(decoded.positions.size(), original.positions.size());
    ASSERT_TRUE(decoded.has_uvs());
    const double step = 1000.0 / ((1 << bits) - 1);  // the sphere's box is 1000 Å on a side
    // Each decoded position next to exactly one original position, within half a step per axis.
    std::vector<std::uint32_t> to_original(decoded.positions.size());
    for (std::size_t v = 0; v < decoded.positions.size(); ++v) {
      std::size_t nearest = 0;
      for (std::size_t o = 1; o < original.positions.size(); ++o)
        if (glm::length(original.positions[o] - decoded.positions[v]) < glm::length(original.positions[nearest] - decoded.positions[v]))
          nearest = o;
      const glm::dvec3 d = glm::abs(original.positions[nearest] - decoded.positions[v]);
      EXPECT_LE(std::max({d.x, d.y, d.z}), 0.5 * step + 1000.0 * 1e-6) << v;  // plus Draco's float dequantisation
      to_original[v] = std::uint32_t(nearest);
    }
    const auto canonical = [](Triangle t) {  // the rotation starting at the smallest index
      while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
      return t;
    };
    std::set<Triangle> expected, got;
    for (const Triangle& t : original.triangles) expected.insert(canonical(t));
    for (const Triangle& t : decoded.triangles) got.insert(canonical({to_original[t[0]], to_original[t[1]], to_original[t[2]]}));
    EXPECT_EQ(got, expected);
    EXPECT_LT(bytes.size(), std::filesystem::file_size(obj_file) / 4);
  }
}

TEST(MeshReader, FormatFromTheExtension) {
  EXPECT_EQ(mesh_format_of("a/b.obj"), MeshFormat::obj);
  EXPECT_EQ(mesh_format_of("B.OFF"), MeshFormat::off);
  EXPECT_EQ(mesh_format_of("c.Ply"), MeshFormat::ply);
  EXPECT_EQ(mesh_format_of("d.stl"), MeshFormat::stl);
  EXPECT_EQ(mesh_format_of("e.drc"), MeshFormat::draco);
  EXPECT_EQ(mesh_format_of("f.DAE"), MeshFormat::collada);
  EXPECT_EQ(mesh_format_of("f.zae"), std::nullopt);
  EXPECT_EQ(mesh_format_of("obj"), std::nullopt);
  EXPECT_EQ(mesh_format_of("g.obj.gz"), std::nullopt);
}

// parse_proxy_mesh is what read_proxy_mesh does with the file's bytes: the same mesh from memory as
// from the file, and the same errors, naming the label it is given.
TEST(MeshReader, ParsesBytesInMemoryAsItReadsTheFile) {
  TempDir dir;
  const ProxyMesh octahedron = read_proxy_mesh(dir.write("octa.obj", testing::octahedron));
  const std::vector<std::byte> drc = encode_draco_mesh(octahedron);
  const std::pair<std::string, std::string> files[] = {
      {"octa.obj", testing::octahedron},
      {"quad.off", "OFF\n4 1 0\n0 0 0\n2 0 0\n3 1 0\n0 1 0\n4 0 1 2 3\n"},
      {"tri.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"tri.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n"},
      {"octa.drc", std::string(reinterpret_cast<const char*>(drc.data()), drc.size())}};
  for (const auto& [name, bytes] : files) {
    SCOPED_TRACE(name);
    const ProxyMesh from_file = read_proxy_mesh(dir.write(name, bytes));
    const ProxyMesh from_memory =
        parse_proxy_mesh(std::as_bytes(std::span(bytes.data(), bytes.size())), *mesh_format_of(name), "memory");
    EXPECT_EQ(from_memory.positions, from_file.positions);
    EXPECT_EQ(from_memory.triangles, from_file.triangles);
    EXPECT_EQ(from_memory.uvs, from_file.uvs);
    EXPECT_EQ(from_memory.uv_triangles, from_file.uv_triangles);
    EXPECT_EQ(from_memory.normals, from_file.normals);
    EXPECT_EQ(from_memory.normal_triangles, from_file.normal_triangles);
  }
  const std::string bad = "v 0 0 0\nf 1 2 3\n";
  try {
    parse_proxy_mesh(std::as_bytes(std::span(bad.data(), bad.size())), MeshFormat::obj, "label.obj");
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "label.obj");
    EXPECT_EQ(e.where(), "line 2, face 0");
  }
}

// Found by draco_fuzzer: a Draco file with unquantised texture coordinates can hold NaN or
// infinity, which were taken as UVs (positions were checked, texture coordinates were not).
TEST(MeshReader, DracoValuesThatAreNotFiniteAreRefused) {
  TempDir dir;
  ProxyMesh mesh = read_proxy_mesh(dir.write("octa.obj", testing::octahedron));
  const auto write_drc = [&](const std::string& name, const ProxyMesh& m) {
    const std::vector<std::byte> bytes = encode_draco_mesh(m, {.position_bits = 0, .uv_bits = 0, .normal_bits = 0});  // 0: unquantised
    return dir.write(name, std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  };
  const auto expect_refused = [](const std::filesystem::path& file, const std::string& rule) {
    try {
      read_proxy_mesh(file);
      ADD_FAILURE() << "no InputError for " << file;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), file.string());
      EXPECT_EQ(e.where().rfind("face ", 0), 0u) << e.what();  // Draco orders the faces its own way
      EXPECT_EQ(e.rule(), rule);
    }
  };
  ProxyMesh bad_uv = mesh;
  bad_uv.uvs[3].y = std::numeric_limits<double>::quiet_NaN();
  expect_refused(write_drc("uv.drc", bad_uv), "texture coordinate is not a finite number");
  ProxyMesh bad_position = mesh;
  bad_position.positions[5].x = std::numeric_limits<double>::infinity();
  expect_refused(write_drc("position.drc", bad_position), "coordinate is not a finite number");
  // Normals that are not finite are not used: computed instead, as for a file without normals.
  ProxyMesh bad_normal = mesh;
  bad_normal.normals[0].z = std::numeric_limits<double>::quiet_NaN();
  const ProxyMesh read = read_proxy_mesh(write_drc("normal.drc", bad_normal));
  for (const glm::dvec3& n : read.normals) EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
}

// Found by draco_fuzzer: libdraco decodes these files into meshes it leaves to the caller to check.
// The first one's faces refer to values its position attribute does not hold; reading them read
// through a null buffer (undefined behaviour; past the end of a buffer for other indices).
TEST(MeshReader, CorruptDracoAttributesAreRefused) {
  TempDir dir;
  const unsigned char corrupt[] = {
      0x44, 0x52, 0x41, 0x43, 0x4f, 0x02, 0x02, 0x01, 0x00, 0x00, 0x00, 0x04, 0x00, 0x04, 0x04, 0x01, 0x32,
      0x00, 0x02, 0x03, 0x00, 0x03, 0x01, 0x02, 0x01, 0x03, 0x01, 0x01, 0x00, 0x01, 0x03, 0x00, 0x00, 0x00,
      0x00, 0x04, 0x00, 0xff, 0xff, 0xff, 0xe1, 0xd2, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x80, 0x3f};
  const auto file = dir.write("corrupt.drc", std::string(reinterpret_cast<const char*>(corrupt), sizeof corrupt));
  expect_input_error(file, "face 0", "corrupt file");
  // Positions declared as bools, whose bytes libdraco would load as bool whatever they hold
  // (undefined behaviour unless 0 or 1): not positions at all.
  const unsigned char bools[] = {
      0x44, 0x52, 0x41, 0x43, 0x4f, 0x02, 0x02, 0x01, 0x00, 0x00, 0x00, 0x04, 0x01, 0x04, 0x00, 0x09, 0x02, 0x00,
      0x02, 0x03, 0x00, 0x03, 0x01, 0x02, 0x01, 0x13, 0x01, 0x01, 0x00, 0x0b, 0x09, 0x00, 0x00, 0x00, 0x00, 0x26,
      0x00, 0x00, 0x00, 0x2d, 0x28, 0x2d, 0x2d, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x00, 0x2d, 0x44, 0x2d};
  expect_input_error(dir.write("bools.drc", std::string(reinterpret_cast<const char*>(bools), sizeof bools)), "",
                     "no readable positions");
}

// Found by draco_fuzzer: libdraco sizes its tables by the counts a file declares before it reads
// what they count. This 36-byte file (bitstream 1.5, edgebreaker) declares 19,398,656 faces, for
// which libdraco 1.5.5 took 460 MB before failing; the counts are now read first and refused.
TEST(MeshReader, DracoFilesDeclaringMoreThanTheReaderDecodesAreRefused) {
  TempDir dir;
  const unsigned char declared[] = {0x44, 0x52, 0x41, 0x43, 0x4f, 0x01, 0x05, 0x01, 0x01, 0x00, 0x00, 0x00,
                                    0x03, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x28, 0x01,
                                    0x02, 0x00, 0x06, 0xfd, 0x00, 0x00, 0x00, 0x00, 0x00, 0x0f, 0x80, 0x3f};
  expect_input_error(dir.write("declared.drc", std::string(reinterpret_cast<const char*>(declared), sizeof declared)), "",
                     "declares 19398656 faces and 0 points, more than this reader decodes");
  // The same in bitstream 2.2 (varints): a billion faces.
  const char billion[] = "DRACO\x02\x02\x01\x01\x00\x00\x00\x03\x80\x94\xeb\xdc\x03\x00\x00\x00";
  expect_input_error(dir.write("billion.drc", std::string(billion, sizeof billion - 1)), "", "declares 1000000000 faces");
  // Varints of more than 32 bits, which libdraco wraps: read as it reads them (685,539,327 faces:
  // a 2.7 GB vector reserved, found by draco_fuzzer after the first limits, which read them otherwise).
  const unsigned char wrapping[] = {
      0x44, 0x52, 0x41, 0x43, 0x4f, 0x02, 0x02, 0x01, 0x01, 0x00, 0x00, 0x00, 0xfa, 0xf7, 0xfd, 0xf7, 0x70, 0xff,
      0xff, 0xf1, 0xc6, 0x02, 0x09, 0xff, 0xff, 0xf1, 0xc6, 0x02, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xfa,
      0xf7, 0xfd, 0xf7, 0x2f, 0xff, 0xff, 0xf1, 0xc6, 0x02, 0x09, 0xff, 0xff, 0xf1, 0xc6, 0x02, 0x01, 0x00, 0x0f};
  expect_input_error(dir.write("wrapping.drc", std::string(reinterpret_cast<const char*>(wrapping), sizeof wrapping)), "",
                     "declares 685539327 faces");
  // Metadata whose one entry declares a 4 GB value in a 20-byte file.
  const char metadata[] = "DRACO\x02\x02\x01\x01\x00\x80\x00\x01\x01" "a\xff\xff\xff\xff\x0f";
  expect_input_error(dir.write("metadata.drc", std::string(metadata, sizeof metadata - 1)), "", "metadata runs past the end");
  // A file libdraco's encoder wrote still reads.
  const ProxyMesh octahedron = read_proxy_mesh(dir.write("octa.obj", testing::octahedron));
  const std::vector<std::byte> drc = encode_draco_mesh(octahedron);
  EXPECT_EQ(parse_proxy_mesh(drc, MeshFormat::draco, "octa.drc").triangles.size(), 8u);
}

TEST(ObjWriter, FormatsPerCornerIndices) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write("octa.obj", testing::octahedron));
  const std::string text = format_obj(mesh);
  EXPECT_NE(text.find("\nv 1 0 0\n"), std::string::npos);
  EXPECT_NE(text.find("\nvt 0.5 0.5\n"), std::string::npos);
  // Face 5 of the octahedron: vertex 6 (−Z) with its own UV (0, 1) — a seam corner.
  EXPECT_NE(text.find("\nvt 0 1\n"), std::string::npos);
  EXPECT_EQ(std::count(text.begin(), text.end(), 'f'), 8);
}

TEST(ObjWriter, RoundTripPreservesPositionsUvsAndNormals) {
  TempDir dir;
  const ProxyMesh original = make_sphere_mesh(432, 500.0);
  const auto file = dir.path() / "sphere.obj";
  write_obj(file, original);
  const ProxyMesh loaded = read_proxy_mesh(file);
  ASSERT_EQ(loaded.triangles.size(), original.triangles.size());
  ASSERT_EQ(loaded.positions.size(), original.positions.size());
  ASSERT_TRUE(loaded.has_uvs());
  ASSERT_TRUE(loaded.has_normals());
  // The writer's 17 digits read back to the same doubles; a unit normal may move by its last bit
  // when normalised again.
  for (std::size_t t = 0; t < original.triangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(loaded.corner_position(t, c), original.corner_position(t, c));
      EXPECT_EQ(loaded.corner_uv(t, c), original.corner_uv(t, c));
      EXPECT_NEAR(glm::length(loaded.corner_normal(t, c) - original.corner_normal(t, c)), 0.0, 1e-15);
    }
  }
}

TEST(ObjWriter, UnwritablePathThrowsAndLeavesNothing) {
  TempDir dir;
  const ProxyMesh mesh = make_sphere_mesh(48, 1.0);
  EXPECT_THROW(write_obj(dir.path() / "no_such_dir" / "x.obj", mesh), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(VertexNormals, AngleWeightedNormalOfCubeCornerIsTheDiagonal) {
  // Three faces of a cube meet at the origin, split into triangles unevenly (two triangles on
  // one face): angle weighting still gives the symmetric diagonal, area weighting would not.
  ProxyMesh mesh;
  mesh.positions = {{0, 0, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}, {-1, -1, 0}};
  mesh.triangles = {{0, 4, 2}, {0, 1, 4}, {0, 2, 3}, {0, 3, 1}};  // all wind towards +x, +y, +z
  compute_angle_weighted_normals(mesh);
  const glm::dvec3 expected = glm::normalize(glm::dvec3(1, 1, 1));
  EXPECT_NEAR(glm::length(mesh.normals[0] - expected), 0.0, 1e-12);
  EXPECT_EQ(mesh.normal_triangles, mesh.triangles);
}

TEST(ProxyMesh, UnitDirectionWithoutUnderflowOrOverflow) {
  // As v / |v| to the last bit where the squares are exact...
  for (const glm::dvec3 v : {glm::dvec3(3, 4, 0), glm::dvec3(-0.1, 2.5e-7, 1e3), glm::dvec3(1e-140, -3e-141, 0)})
    EXPECT_EQ(unit_direction(v), v / glm::length(v));
  // ...and unit length where they would underflow or overflow.
  for (const glm::dvec3 v : {glm::dvec3(1e-170, 0, 0), glm::dvec3(3e-162, -4e-162, 0), glm::dvec3(1e300, 1e300, -1e300),
                             glm::dvec3(4.9e-324, 0, 0)}) {
    const std::optional<glm::dvec3> unit = unit_direction(v);
    ASSERT_TRUE(unit);
    EXPECT_NEAR(glm::length(*unit), 1.0, 1e-15);
    EXPECT_NEAR(glm::length(*unit - glm::normalize(v / std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}))), 0.0, 1e-15);
  }
  EXPECT_EQ(unit_direction(glm::dvec3(0.0)), std::nullopt);
  EXPECT_EQ(unit_direction(glm::dvec3(1, std::numeric_limits<double>::quiet_NaN(), 0)), std::nullopt);
  EXPECT_EQ(unit_direction(glm::dvec3(std::numeric_limits<double>::infinity(), 0, 0)), std::nullopt);
}

// Found by draco_fuzzer: a vertex far from the others (the angle at it 3e-162 rad here) has an
// angle-weighted sum whose squares underflow; its "normal" came out 4.6 % short of unit length.
TEST(VertexNormals, UnitEvenWhereTheAnglesAtAVertexAreTiny) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write("needle.obj", "v 1e100 0 0\nv 0 0 0\nv 0 3e-62 0\nf 1 2 3\n"));
  ASSERT_EQ(mesh.normals.size(), 3u);
  for (const glm::dvec3& n : mesh.normals) EXPECT_EQ(n, glm::dvec3(0, 0, -1));
}

}  // namespace
}  // namespace nano::mesh
