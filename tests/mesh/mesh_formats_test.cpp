// The mesh readers on what each format allows (the files real tools write: comments before an OFF
// keyword, PLY in both byte orders with extra properties and elements, OBJ n-gons and negative
// indices, binary STL headers starting with "solid") and on hostile files (truncated, counts larger
// than the file, garbage). Every test writes its own file (bake/mesh/mesh_reader.hpp).
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "bake/mesh/mesh_reader.hpp"
#include "tests/mesh/test_obj.hpp"

namespace nano::mesh {
namespace {

using testing::expect_input_error;
using testing::TempDir;

using Corners = std::array<glm::dvec3, 3>;

std::vector<Corners> corners_of(const ProxyMesh& mesh) {
  std::vector<Corners> out;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    out.push_back({mesh.corner_position(t, 0), mesh.corner_position(t, 1), mesh.corner_position(t, 2)});
  return out;
}

// A quad whose diagonal 1–3 (√5) is shorter than 0–2 (√10): cut into (0 1 3) and (1 2 3).
const glm::dvec3 kQuad[4] = {{0, 0, 0}, {2, 0, 0}, {3, 1, 0}, {0, 1, 0}};
const std::vector<Corners> kQuadSplit = {{kQuad[0], kQuad[1], kQuad[3]}, {kQuad[1], kQuad[2], kQuad[3]}};
// A quad whose diagonal 0–2 (√2) is the shorter one (√10 for 1–3): cut into (0 1 2) and (0 2 3).
const glm::dvec3 kOtherQuad[4] = {{0, 0, 5}, {1, 0, 5}, {1, 1, 5}, {-2, 1, 5}};
const std::vector<Corners> kOtherQuadSplit = {{kOtherQuad[0], kOtherQuad[1], kOtherQuad[2]},
                                              {kOtherQuad[0], kOtherQuad[2], kOtherQuad[3]}};

// The bytes of a binary file in either byte order.
class Bytes {
public:
  explicit Bytes(bool big_endian = false) : big_endian_(big_endian) {}
  Bytes& text(std::string_view s) {
    data += s;
    return *this;
  }
  template <typename T>
  Bytes& put(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (big_endian_ != (std::endian::native == std::endian::big)) std::reverse(raw, raw + sizeof(T));
    data.append(raw, sizeof(T));
    return *this;
  }
  // A value stored as the PLY type named.
  Bytes& ply(std::string_view type, double v) {
    if (type == "char") return put(static_cast<std::int8_t>(v));
    if (type == "uchar" || type == "uint8") return put(static_cast<std::uint8_t>(v));
    if (type == "short") return put(static_cast<std::int16_t>(v));
    if (type == "ushort") return put(static_cast<std::uint16_t>(v));
    if (type == "int" || type == "int32") return put(static_cast<std::int32_t>(v));
    if (type == "uint" || type == "uint32") return put(static_cast<std::uint32_t>(v));
    if (type == "float") return put(static_cast<float>(v));
    return put(v);
  }
  std::string data;

private:
  bool big_endian_;
};

// ---- OFF ----

TEST(OffReader, CommentsAndBlankLinesAnywhere) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write("cgal.off",
      "# written by a CGAL tool\n#   4 vertices, 1 face\n\n"
      "OFF # the keyword\n\n"
      "4 1 0\n"
      "# the vertices\n"
      "0 0 0  # corner 0\n2 0 0\n\n3 1 0\r\n0 1 0\n"
      "\n"
      "4 0 1 2 3   # a quad\n"));
  EXPECT_EQ(corners_of(mesh), kQuadSplit);
  EXPECT_EQ(mesh.positions.size(), 4u);
  EXPECT_FALSE(mesh.has_uvs());
  ASSERT_TRUE(mesh.has_normals());
  EXPECT_NEAR(glm::length(mesh.corner_normal(0, 0) - glm::dvec3(0, 0, 1)), 0.0, 1e-12);
}

TEST(OffReader, CountsOnTheKeywordLineOrWithoutTheKeyword) {
  TempDir dir;
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  for (const std::string head : {"OFF 3 1 0\n", "OFF\n3 1\n", "3 1 0\n", "OFF\n\n  3   1   0  \n"}) {
    SCOPED_TRACE(head);
    const ProxyMesh mesh = read_proxy_mesh(dir.write("t.off", head + body));
    ASSERT_EQ(mesh.triangles.size(), 1u);
    EXPECT_EQ(mesh.corner_position(0, 1), glm::dvec3(1, 0, 0));
  }
}

TEST(OffReader, NoffNormalsAreKept) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write("n.off",
      "NOFF\n3 1 0\n0 0 0  0 0 2\n1 0 0  1 0 0\n0 1 0  0 0 1\n3 0 1 2\n"));
  ASSERT_TRUE(mesh.has_normals());
  EXPECT_EQ(mesh.corner_normal(0, 0), glm::dvec3(0, 0, 1));  // normalised
  EXPECT_EQ(mesh.corner_normal(0, 1), glm::dvec3(1, 0, 0));  // the file's, not the face's
}

TEST(OffReader, CoffColoursAreIgnored) {
  TempDir dir;
  // Vertex colours of 4 and 3 components, face colours as integers and as floats.
  const ProxyMesh mesh = read_proxy_mesh(dir.write("c.off",
      "COFF\n4 2 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0\n1 1 0 0 0 255 128\n0 1 0 0.5 0.5 0.5 1\n"
      "3 0 1 2 255 0 0\n3 0 2 3 1.0 0.0 0.0 0.5\n"));
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.corner_position(1, 2), glm::dvec3(0, 1, 0));
  EXPECT_FALSE(mesh.has_uvs());
}

TEST(OffReader, TextureCoordinatesAreKeptAsUvs) {
  TempDir dir;
  struct Case {
    const char* name;
    std::string text;
    bool normals;
  };
  const Case cases[] = {
      {"STOFF", "STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1 0.25\n0 1 0 0 1\n3 0 1 2\n", false},
      {"NSTOFF", "NSTOFF\n3 1 0\n0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0.25\n0 1 0 0 0 1 0 1\n3 0 1 2\n", true},
      // Colours run to the end of the line: the UVs are its last two numbers (3 and 4 components).
      {"STCOFF", "STCOFF\n3 1 0\n0 0 0 1 0 0 0 0\n1 0 0 0 1 0 1 1 0.25\n0 1 0 0 0 1 0 1\n3 0 1 2\n", false},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const ProxyMesh mesh = read_proxy_mesh(dir.write("t.off", c.text));
    ASSERT_EQ(mesh.triangles.size(), 1u);
    ASSERT_TRUE(mesh.has_uvs());
    EXPECT_EQ(mesh.corner_uv(0, 0), glm::dvec2(0, 0));
    EXPECT_EQ(mesh.corner_uv(0, 1), glm::dvec2(1, 0.25));
    EXPECT_EQ(mesh.corner_uv(0, 2), glm::dvec2(0, 1));
    if (c.normals) {
      EXPECT_EQ(mesh.corner_normal(0, 1), glm::dvec3(0, 0, 1));
    }
  }
}

// Twice the area of a triangle of the plane z = const, positive when counter-clockwise seen from +z.
double twice_area_xy(const Corners& c) {
  return (c[1].x - c[0].x) * (c[2].y - c[0].y) - (c[1].y - c[0].y) * (c[2].x - c[0].x);
}

TEST(OffReader, PolygonsOfAnySize) {
  TempDir dir;
  // A pentagon (area 5: cut along diagonals inside it, polygon_triangulation_test.cpp), the quad
  // (shorter diagonal) and a triangle padded to a quad.
  const ProxyMesh mesh = read_proxy_mesh(dir.write("p.off",
      "OFF\n9 3 0\n"
      "0 0 9\n2 0 9\n3 1 9\n1 2 9\n-1 1 9\n"
      "0 0 0\n2 0 0\n3 1 0\n0 1 0\n"
      "5 0 1 2 3 4\n4 5 6 7 8\n4 5 6 7 7\n"));
  ASSERT_EQ(mesh.triangles.size(), 6u);
  double twice_area = 0.0;
  for (std::size_t t = 0; t < 3; ++t) {
    const Corners c{mesh.corner_position(t, 0), mesh.corner_position(t, 1), mesh.corner_position(t, 2)};
    EXPECT_GT(twice_area_xy(c), 0.0);
    for (const glm::dvec3& p : c) EXPECT_EQ(p.z, 9.0);
    twice_area += twice_area_xy(c);
  }
  EXPECT_DOUBLE_EQ(twice_area, 10.0);
  const std::vector<Corners> all = corners_of(mesh);
  EXPECT_EQ(std::vector<Corners>(all.begin() + 3, all.begin() + 5), kQuadSplit);
  EXPECT_EQ(all[5], (Corners{kQuad[0], kQuad[1], kQuad[2]}));
}

TEST(OffReader, HostileFilesAreRefusedByName) {
  TempDir dir;
  const std::string triangle = "0 0 0\n1 0 0\n0 1 0\n";
  expect_input_error(dir.write("empty.off", ""), "", "empty");
  expect_input_error(dir.write("huge.off", "OFF\n1000000000 1 0\n0 0 0\n"), "line 2", "cannot fit");
  expect_input_error(dir.write("negative.off", "OFF\n-3 1 0\n"), "line 2", "negative");
  expect_input_error(dir.write("short.off", "OFF\n3 1 0\n0.000 0.000 0.000\n1.000 0.000 0.000\n"), "line 4",
                     "ends in vertex 2 of 3");
  expect_input_error(dir.write("noface.off", "OFF\n3 2 0\n" + triangle + "3 0 1 2\n"), "line 6", "ends in face 1 of 2");
  expect_input_error(dir.write("garbage.off", std::string("\x7f" "ELF\x02\x01\x01 junk\n")), "line 1", "not an OFF file");
  expect_input_error(dir.write("word.off", "OFF\n3 1 0\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n"), "line 4", "not a number");
  expect_input_error(dir.write("4d.off", "4OFF\n3 1 0\n"), "line 1", "4D");
  expect_input_error(dir.write("binary.off", "OFF BINARY\n"), "line 1", "binary OFF");
  expect_input_error(dir.write("range.off", "OFF\n3 1 0\n" + triangle + "3 0 1 7\n"), "line 6, face 0", "does not exist");
  expect_input_error(dir.write("corners.off", "OFF\n3 1 0\n" + triangle + "2000000000 0 1 2\n"), "line 6", "more corners");
  expect_input_error(dir.write("nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"), "line 4, vertex 1", "finite");
  expect_input_error(dir.write("repeat.off", "OFF\n3 1 0\n" + triangle + "3 0 1 1\n"), "line 6, face 0", "repeated vertex");
  expect_input_error(dir.write("twice.off", "OFF\n3 1 0\n" + triangle + "5 0 1 0 2 1\n"), "line 6, face 0",
                     "through vertex 0 twice");
  expect_input_error(dir.write("nofaces.off", "OFF\n3 0 0\n" + triangle), "", "no faces");
}

// ---- OBJ ----

TEST(ObjReader, QuadsAreSplitAlongTheShorterDiagonal) {
  TempDir dir;
  std::string obj;
  for (const auto* quad : {kQuad, kOtherQuad})
    for (int k = 0; k < 4; ++k)
      obj += "v " + std::to_string(quad[k].x) + " " + std::to_string(quad[k].y) + " " + std::to_string(quad[k].z) + "\n";
  const ProxyMesh mesh = read_proxy_mesh(dir.write("q.obj", obj + "f 1 2 3 4\nf 5 6 7 8\nf 1 2 3\n"));
  std::vector<Corners> expected = kQuadSplit;
  expected.insert(expected.end(), kOtherQuadSplit.begin(), kOtherQuadSplit.end());
  expected.push_back({kQuad[0], kQuad[1], kQuad[2]});
  EXPECT_EQ(corners_of(mesh), expected);
}

// An n-gon becomes n − 2 triangles of its own corners in its winding, tiling it (area 12 here);
// which diagonals: polygon_triangulation_test.cpp.
TEST(ObjReader, NgonsAreCutIntoTrianglesInsideThem) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write("hex.obj",
      "v 2 0 0\nv 1 2 0\nv -1 2 0\nv -2 0 0\nv -1 -2 0\nv 1 -2 0\nf 1 2 3 4 5 6\n"));
  ASSERT_EQ(mesh.triangles.size(), 4u);
  double twice_area = 0.0;
  for (const Corners& c : corners_of(mesh)) {
    EXPECT_GT(twice_area_xy(c), 0.0);
    twice_area += twice_area_xy(c);
  }
  EXPECT_DOUBLE_EQ(twice_area, 24.0);
}

TEST(ObjReader, NegativeIndicesCountBackFromTheLastOneRead) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write("neg.obj",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
      "f -3/-3/-1 -2/-2/-1 -1/-1/-1\n"
      "v 1 1 0\nvt 1 1\n"
      "f -3/-3 -1/-1 -2/-2\n"));
  ASSERT_EQ(mesh.triangles.size(), 2u);
  ASSERT_TRUE(mesh.has_uvs());
  // Every UV of this file is its position's x and y.
  for (std::size_t t = 0; t < 2; ++t)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(mesh.corner_uv(t, c), glm::dvec2(mesh.corner_position(t, c))) << t << c;
  EXPECT_EQ(mesh.corner_position(1, 0), glm::dvec3(1, 0, 0));
  EXPECT_EQ(mesh.corner_position(1, 1), glm::dvec3(1, 1, 0));
}

TEST(ObjReader, EveryCornerFormAndTheStatementsThatAreSkipped) {
  TempDir dir;
  const std::string head =
      "# exported by hand\nmtllib scene.mtl\no part\ng skin\ns 1\nusemtl red\n"
      "v 0 0 0 1.0   # a w\nv 1 0 0 0.5 0.5 0.5\nv 0 1 0\nv 1 1 0\n"
      "vt 0\nvt 1 0 0\nvt 0 1\nvt 1 1\nvn 0 0 2\nvn 0 0 1\nl 1 2\np 3\ns off\ng\n";
  // v/vt/vn with a continued line, then v//vn: normals everywhere, UVs not.
  ProxyMesh mesh = read_proxy_mesh(dir.write("a.obj", head + "f 1/1/1 2/2/1 \\\n  3/3/2\nf 2//2 4//2 3//2  # last\n"));
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_FALSE(mesh.has_uvs());
  ASSERT_TRUE(mesh.has_normals());
  EXPECT_EQ(mesh.corner_normal(0, 0), glm::dvec3(0, 0, 1));
  EXPECT_EQ(mesh.corner_position(1, 1), glm::dvec3(1, 1, 0));
  // v/vt: UVs everywhere ("vt 0" is u = 0, v = 0), normals computed.
  mesh = read_proxy_mesh(dir.write("b.obj", head + "f 1/1 2/2 3/3\nf 2/2 4/4 3/3\n"));
  ASSERT_TRUE(mesh.has_uvs());
  EXPECT_EQ(mesh.corner_uv(0, 0), glm::dvec2(0, 0));
  EXPECT_EQ(mesh.corner_uv(1, 1), glm::dvec2(1, 1));
  // Plain v, and "fo", the old name of f.
  mesh = read_proxy_mesh(dir.write("c.obj", head + "f 1 2 3\nfo 2 4 3\n"));
  EXPECT_EQ(mesh.triangles.size(), 2u);
}

TEST(ObjReader, HostileFilesAreRefusedByName) {
  TempDir dir;
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expect_input_error(dir.write("back.obj", triangle + "f -4 -2 -1\n"), "line 4", "counts back past the first vertex");
  expect_input_error(dir.write("zero.obj", triangle + "f 0 1 2\n"), "line 4", "start at 1");
  expect_input_error(dir.write("corner.obj", triangle + "f 1/x 2 3\n"), "line 4", "not of the form");
  expect_input_error(dir.write("slashes.obj", triangle + "f 1/1/1/1 2 3\n"), "line 4", "more than three");
  expect_input_error(dir.write("uv.obj", triangle + "f 1/5 2/5 3/5\n"), "line 4, face 0", "texture coordinate that does not exist");
  expect_input_error(dir.write("normal.obj", triangle + "f 1//2 2//2 3//2\n"), "line 4, face 0", "normal that does not exist");
  expect_input_error(dir.write("two.obj", "v 1 2\n"), "line 1", "needs x, y and z");
  expect_input_error(dir.write("word.obj", "v 1 2 three\n"), "line 1", "not a number");
  expect_input_error(dir.write("small.obj", triangle + "f 1 2\n"), "line 4, face 0", "fewer than 3");
  // Line numbers count physical lines, continued ones included.
  expect_input_error(dir.write("lines.obj", "v 0 0 0\nv 1 0 \\\n 0\nv 0 1 0\nf 1 2 \\\n 3\nf 1 2 7\n"), "line 7, face 1",
                     "does not exist");
}

// ---- PLY ----

TEST(PlyReader, AsciiWithExtraPropertiesAndElements) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write("scan.ply",
      "ply\nformat ascii 1.0\ncomment from a scanner\nobj_info nothing useful\n"
      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float confidence\n"
      "property float nx\nproperty float ny\nproperty float nz\nproperty float s\nproperty float t\n"
      "element edge 2\nproperty int vertex1\nproperty int vertex2\nproperty list uchar int more\n"
      "element face 1\nproperty list uchar uint vertex_index\nproperty uchar quality\n"
      "end_header\n"
      "0 0 0 255 0 0 0.9 0 0 1 0 0\n"
      "2 0 0 255 0 0 0.9 0 0 1 0.5 0\n"
      "3 1 0 255 0 0 0.9 0 0.6 0.8 1 1\n"
      "0 1 0 255 0 0 0.9 0 0 1 0 1\n"
      "0 1 2 7 8\n1 2 0\n"
      "4 0 1 2 3 200\n"));
  EXPECT_EQ(corners_of(mesh), kQuadSplit);
  ASSERT_TRUE(mesh.has_uvs());
  EXPECT_EQ(mesh.corner_uv(1, 0), glm::dvec2(0.5, 0));  // triangle (1 2 3)
  EXPECT_EQ(mesh.corner_uv(1, 1), glm::dvec2(1, 1));
  ASSERT_TRUE(mesh.has_normals());
  EXPECT_NEAR(glm::length(mesh.corner_normal(1, 1) - glm::dvec3(0, 0.6, 0.8)), 0.0, 1e-15);
  EXPECT_EQ(mesh.corner_normal(1, 0), glm::dvec3(0, 0, 1));
}

// The same mesh in both byte orders, with types of every width, an element to skip (with a list
// of its own) between the vertices and the faces, and a scalar after the index list.
std::string binary_ply(bool big_endian, std::string_view count_type, std::string_view index_type) {
  Bytes b(big_endian);
  b.text("ply\nformat ").text(big_endian ? "binary_big_endian" : "binary_little_endian").text(" 1.0\n");
  b.text("comment binary\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n");
  b.text("property uchar red\nproperty float quality\nproperty float texture_u\nproperty float texture_v\n");
  b.text("element edge 2\nproperty int vertex1\nproperty int vertex2\nproperty list uchar short extra\n");
  b.text("element face 1\nproperty list ").text(count_type).text(" ").text(index_type).text(" vertex_indices\n");
  b.text("property uchar flags\nend_header\n");
  for (const glm::dvec3& p : kQuad) b.put(p.x).put(p.y).put(p.z).put<std::uint8_t>(200).put(0.5f).put(float(p.x / 4)).put(float(p.y));
  for (int e = 0; e < 2; ++e) b.put<std::int32_t>(e).put<std::int32_t>(e + 1).put<std::uint8_t>(2).put<std::int16_t>(-1).put<std::int16_t>(7);
  b.ply(count_type, 4);
  for (int v = 0; v < 4; ++v) b.ply(index_type, v);
  b.put<std::uint8_t>(1);
  return b.data;
}

TEST(PlyReader, BinaryInBothByteOrdersWithAnyListTypes) {
  TempDir dir;
  const std::pair<const char*, const char*> list_types[] = {
      {"uchar", "int"}, {"uint8", "uint32"}, {"int", "uint"}, {"ushort", "short"}, {"char", "uchar"}};
  for (const bool big_endian : {false, true}) {
    for (const auto& [count_type, index_type] : list_types) {
      SCOPED_TRACE(std::string(big_endian ? "big " : "little ") + count_type + " " + index_type);
      const ProxyMesh mesh = read_proxy_mesh(dir.write("b.ply", binary_ply(big_endian, count_type, index_type)));
      EXPECT_EQ(corners_of(mesh), kQuadSplit);
      ASSERT_TRUE(mesh.has_uvs());
      for (std::size_t t = 0; t < 2; ++t)
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(mesh.corner_uv(t, c), glm::dvec2(mesh.corner_position(t, c).x / 4, mesh.corner_position(t, c).y));
    }
  }
}

TEST(PlyReader, PerCornerTexcoordsAsMeshLabWritesThem) {
  TempDir dir;
  // Vertex 0 has a different UV in each face: a seam.
  const ProxyMesh mesh = read_proxy_mesh(dir.write("seam.ply",
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 2\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\nend_header\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
      "3 0 1 2 6 0 0 1 0 1 1\n3 0 2 3 6 0.5 0.5 1 1 0 1\n"));
  ASSERT_TRUE(mesh.has_uvs());
  EXPECT_EQ(mesh.corner_uv(0, 0), glm::dvec2(0, 0));
  EXPECT_EQ(mesh.corner_uv(1, 0), glm::dvec2(0.5, 0.5));
  EXPECT_EQ(mesh.corner_uv(1, 2), glm::dvec2(0, 1));
}

TEST(PlyReader, HostileFilesAreRefusedByName) {
  TempDir dir;
  const std::string good = binary_ply(false, "uchar", "int");
  expect_input_error(dir.write("truncated.ply", good.substr(0, good.size() - 1)), "face 0", "ends inside this entry (truncated)");
  expect_input_error(dir.write("truncated_list.ply", good.substr(0, good.size() - 3)), "face 0",
                     "list 'vertex_indices' of 4 items runs past the end of the file (truncated)");
  expect_input_error(dir.write("cut_vertices.ply", good.substr(0, good.find("end_header\n") + 11 + 40)), "line 4",
                     "more than the 40 bytes");
  std::string huge = good;
  huge.replace(huge.find("element vertex 4"), 16, "element vertex 400000000");
  expect_input_error(dir.write("huge.ply", huge), "line 4", "more than");
  std::string long_list = binary_ply(false, "uint", "int");
  const std::size_t count_at = long_list.size() - 1 - 4 * 4 - 4;  // the face's list count, before 4 indices and the flags
  long_list.replace(count_at, 4, "\xff\xff\xff\xff");
  expect_input_error(dir.write("long_list.ply", long_list), "face 0", "runs past the end");
  std::string negative_list = binary_ply(false, "char", "int");
  negative_list[negative_list.size() - 1 - 4 * 4 - 1] = '\xff';
  expect_input_error(dir.write("negative_list.ply", negative_list), "face 0", "negative length");

  const std::string ascii_head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  expect_input_error(dir.write("short.ply", ascii_head + "0.0 0.0 0.0\n1.0 0.0 0.0\n"), "line 11, vertex 2",
                     "ends inside");
  expect_input_error(dir.write("word.ply", ascii_head + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n"), "line 11, vertex 1",
                     "not a number");
  expect_input_error(dir.write("range.ply", ascii_head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n"), "line 13, face 0",
                     "does not exist");
  expect_input_error(dir.write("negative.ply", "ply\nformat ascii 1.0\nelement vertex -5\nend_header\n"), "line 3",
                     "at least 0");
  expect_input_error(dir.write("encoding.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n"), "line 2",
                     "unknown encoding");
  expect_input_error(dir.write("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n"),
                     "line 4", "unknown property type");
  expect_input_error(dir.write("zip.ply", std::string("PK\x03\x04 not a mesh")), "", "not a PLY file");
  expect_input_error(dir.write("open.ply", "ply\nformat ascii 1.0\nelement vertex 0\n"), "", "end_header");
  expect_input_error(dir.write("noindices.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
                                                "property float y\nproperty float z\nelement face 0\n"
                                                "property int vertex_indices\nend_header\n"),
                     "line 7", "no vertex_indices list");
}

// A vertex index list of floats or doubles, or an ASCII index of 2^63 or more, was cast to int64 as
// it came: undefined for NaN and for values no int64 holds (seen reading the reader for the
// fuzzers; ply_fuzzer's UBSan reports it on these files).
TEST(PlyReader, IndicesThatAreNotWholeOrTooLargeAreRefused) {
  TempDir dir;
  const auto ply = [](std::string_view index_type, std::string_view face) {
    return "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
           "element face 1\nproperty list uchar " + std::string(index_type) + " vertex_indices\nend_header\n"
           "0 0 0\n1 0 0\n0 1 0\n" + std::string(face) + "\n";
  };
  expect_input_error(dir.write("nan.ply", ply("float", "3 nan 0 1")), "line 13, face 0", "vertex index nan is not a whole number");
  expect_input_error(dir.write("half.ply", ply("double", "3 0.5 0 1")), "line 13, face 0", "vertex index 0.5 is not a whole number");
  expect_input_error(dir.write("huge.ply", ply("double", "3 1e300 0 1")), "line 13, face 0",
                     "vertex index 1.0000000000000001e+300 references a vertex that does not exist");
  expect_input_error(dir.write("int64.ply", ply("int", "3 0 9223372036854775807 1")), "line 13, face 0",
                     "vertex index 9.2233720368547758e+18 references a vertex that does not exist");
  const ProxyMesh mesh = read_proxy_mesh(dir.write("whole.ply", ply("double", "3 0 1.0 2e0")));
  EXPECT_EQ(mesh.triangles.size(), 1u);
}

// ---- STL ----

TEST(StlReader, AsciiWithNamesCapitalsAndTwoSolids) {
  TempDir dir;
  const ProxyMesh mesh = read_proxy_mesh(dir.write("parts.stl",
      "solid my part  (mm)\n"
      "  FACET NORMAL 0 0 1\n    OUTER LOOP\n      VERTEX 0 0 0\n      VERTEX 1 0 0\n      VERTEX 0 1 0\n"
      "    ENDLOOP\n  ENDFACET\n"
      "  facet normal nan nan nan\n    outer loop\n      vertex 1 0 0\n      vertex 1 1 0\n      vertex 0 1 0\n"
      "    endloop\n  endfacet\n"
      "endsolid my part  (mm)\n"
      "solid second\nfacet normal 0 0 1 outer loop vertex 5 5 5 vertex 6 5 5 vertex 5 6 5 endloop endfacet\nendsolid\n"));
  ASSERT_EQ(mesh.triangles.size(), 3u);
  EXPECT_EQ(mesh.positions.size(), 7u);  // the shared edge welded
  EXPECT_EQ(mesh.triangles[1], (Triangle{1, 3, 2}));
  EXPECT_EQ(mesh.corner_position(2, 2), glm::dvec3(5, 6, 5));
  EXPECT_FALSE(mesh.has_uvs());
}

std::string binary_stl(const std::string& header_text, std::uint32_t count, const std::vector<Corners>& triangles) {
  Bytes b;
  b.text(header_text).text(std::string(80 - header_text.size(), ' ')).put(count);
  for (const Corners& t : triangles) {
    b.put(0.0f).put(0.0f).put(1.0f);
    for (const glm::dvec3& p : t) b.put(float(p.x)).put(float(p.y)).put(float(p.z));
    b.put<std::uint16_t>(0);
  }
  return b.data;
}

TEST(StlReader, BinaryEvenWhenItsHeaderSaysSolid) {
  TempDir dir;
  const std::vector<Corners> triangles = {{glm::dvec3(0, 0, 0), glm::dvec3(1.5, 0, 0), glm::dvec3(0, 0.25, 0)},
                                          {glm::dvec3(1.5, 0, 0), glm::dvec3(1.5, 0.25, 0), glm::dvec3(0, 0.25, 0)}};
  for (const std::string header : {"binary STL from a CAD tool", "solid part (binary all the same)"}) {
    SCOPED_TRACE(header);
    const ProxyMesh mesh = read_proxy_mesh(dir.write("b.stl", binary_stl(header, 2, triangles)));
    EXPECT_EQ(corners_of(mesh), triangles);
    EXPECT_EQ(mesh.positions.size(), 4u);
  }
}

TEST(StlReader, HostileFilesAreRefusedByName) {
  TempDir dir;
  const std::vector<Corners> one = {{glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)}};
  expect_input_error(dir.write("truncated.stl", binary_stl("binary", 2, one)), "", "truncated");
  expect_input_error(dir.write("truncated_solid.stl", binary_stl("solid but binary", 2, one)), "", "truncated");
  expect_input_error(dir.write("huge.stl", binary_stl("binary", 0xffffffffu, one)), "", "truncated");
  expect_input_error(dir.write("tiny.stl", "abc"), "", "not an STL file");
  expect_input_error(dir.write("open.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"),
                     "line 5", "ends where 'endloop' should be");
  expect_input_error(dir.write("word.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 zero\n"), "line 4",
                     "not a number");
  expect_input_error(dir.write("junk.stl", "solid t\nfacet normal 0 0 1\ninner loop\n"), "line 3", "'outer'");
  expect_input_error(dir.write("nan.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex inf 0 0\n"
                                          "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n"),
                     "line 5, vertex 1", "finite");
}

}  // namespace
}  // namespace nano::mesh
