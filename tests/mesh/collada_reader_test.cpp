// The Collada reader (bake/mesh/collada_reader.cpp, through Assimp): node transforms applied and
// compared with positions worked out by hand, <unit> and <up_axis> never applied, the same mesh
// as our OBJ reader makes of the same polygons, cellPACK's own export style, and hostile files
// refused as InputErrors naming the file, with nothing printed; what Assimp does not survive (a
// crash, running out of time or of address space) ends its own process, never this one. Every
// test writes its own file.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include <sys/wait.h>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "bake/mesh/mesh_reader.hpp"
#include "bake/mesh/polygon_soup.hpp"
#include "tests/mesh/test_obj.hpp"

namespace nano::mesh {
namespace {

using testing::expect_input_error;
using testing::TempDir;

// A Collada document around `geometries` (library_geometries' content) and `nodes` (the
// visual scene's), with the asset's unit and up axis.
std::string collada(const std::string& geometries, const std::string& nodes, const std::string& unit_meter = "1",
                    const std::string& up_axis = "Y_UP") {
  return "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
         "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
         "  <asset><unit meter=\"" + unit_meter + "\" name=\"u\"/><up_axis>" + up_axis + "</up_axis></asset>\n"
         "  <library_geometries>\n" + geometries + "  </library_geometries>\n"
         "  <library_visual_scenes><visual_scene id=\"scene\">\n" + nodes + "  </visual_scene></library_visual_scenes>\n"
         "  <scene><instance_visual_scene url=\"#scene\"/></scene>\n"
         "</COLLADA>\n";
}

// A geometry `id` of `count` positions (x y z each) and triangles given as position indices.
std::string triangle_geometry(const std::string& id, const std::string& positions, int count, const std::string& triangles,
                              int triangle_count) {
  return "    <geometry id=\"" + id + "\"><mesh>\n"
         "      <source id=\"" + id + "-p\"><float_array id=\"" + id + "-pa\" count=\"" + std::to_string(3 * count) + "\">" +
         positions + "</float_array>\n"
         "        <technique_common><accessor source=\"#" + id + "-pa\" count=\"" + std::to_string(count) +
         "\" stride=\"3\"><param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
         "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
         "      <vertices id=\"" + id + "-v\"><input semantic=\"POSITION\" source=\"#" + id + "-p\"/></vertices>\n"
         "      <triangles count=\"" + std::to_string(triangle_count) + "\"><input semantic=\"VERTEX\" source=\"#" + id +
         "-v\" offset=\"0\"/><p>" + triangles + "</p></triangles>\n"
         "    </mesh></geometry>\n";
}

// The unit tetrahedron, outward.
const std::string kTetrahedron =
    triangle_geometry("tet", "0 0 0  1 0 0  0 1 0  0 0 1", 4, "0 2 1  0 1 3  0 3 2  1 2 3", 4);

// Each expected position has one within `tolerance` among the mesh's, and there are as many.
void expect_positions(const ProxyMesh& mesh, const std::vector<glm::dvec3>& expected, double tolerance) {
  ASSERT_EQ(mesh.positions.size(), expected.size());
  for (const glm::dvec3& e : expected)
    EXPECT_TRUE(std::any_of(mesh.positions.begin(), mesh.positions.end(),
                            [&](const glm::dvec3& p) { return glm::length(p - e) <= tolerance; }))
        << e.x << " " << e.y << " " << e.z;
}

// Every triangle's normal points away from the mesh's centroid (a convex mesh, outward).
bool faces_outward(const ProxyMesh& mesh) {
  glm::dvec3 centre(0.0);
  for (const glm::dvec3& p : mesh.positions) centre += p / double(mesh.positions.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::dvec3 a = mesh.corner_position(t, 0), b = mesh.corner_position(t, 1), c = mesh.corner_position(t, 2);
    if (glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0 - centre) <= 0.0) return false;
  }
  return true;
}

// The tetrahedron under a node (translate 10 20 30) holding a node (rotate 90° about z, scale 2):
// p ↦ (10, 20, 30) + Rz(90°)(2p), that is (x, y, z) ↦ (10 − 2y, 20 + 2x, 30 + 2z). The unit of
// 1 cm and the Z_UP axis are not applied (mesh_reader.hpp).
TEST(ColladaReader, NestedNodeTransformsAreAppliedUnitAndUpAxisAreNot) {
  TempDir dir;
  const std::string nodes =
      "    <node id=\"outer\"><translate>10 20 30</translate>\n"
      "      <node id=\"inner\"><rotate>0 0 1 90</rotate><scale>2 2 2</scale><instance_geometry url=\"#tet\"/></node>\n"
      "    </node>\n";
  const ProxyMesh mesh = read_proxy_mesh(dir.write("tet.dae", collada(kTetrahedron, nodes, "0.01", "Z_UP")));
  ASSERT_EQ(mesh.triangles.size(), 4u);
  // Single-precision cos(π/2) in Assimp's rotation: about 1e-7 off per unit.
  expect_positions(mesh, {{8, 20, 30}, {10, 20, 30}, {10, 20, 32}, {10, 22, 30}}, 1e-5);
  EXPECT_TRUE(faces_outward(mesh));
  EXPECT_FALSE(mesh.has_uvs());
  EXPECT_TRUE(mesh.has_normals());  // computed
}

// Whatever the unit and up axis say, coordinates come back exactly as written.
TEST(ColladaReader, CoordinatesAreTakenAsWrittenWhateverTheUnitAndUpAxis) {
  TempDir dir;
  const std::string geometry = triangle_geometry("t", "0.5 725 -3  1.25 -7 2  -616.722 0 381.155", 3, "0 1 2", 1);
  const std::string nodes = "    <node id=\"n\"><instance_geometry url=\"#t\"/></node>\n";
  for (const std::string unit : {"1", "0.01", "1e-10", "1000"})
    for (const std::string up : {"X_UP", "Y_UP", "Z_UP"}) {
      SCOPED_TRACE(unit + " " + up);
      const ProxyMesh mesh = read_proxy_mesh(dir.write("t.dae", collada(geometry, nodes, unit, up)));
      ASSERT_EQ(mesh.triangles.size(), 1u);
      EXPECT_EQ(mesh.corner_position(0, 0), glm::dvec3(0.5, 725, -3));
      EXPECT_EQ(mesh.corner_position(0, 1), glm::dvec3(1.25, -7, 2));
      EXPECT_EQ(mesh.corner_position(0, 2), glm::dvec3(double(-616.722f), 0, double(381.155f)));  // as floats
    }
}

// Every mesh every node places: the tetrahedron twice (a <matrix> moving it by 5 along x), and a
// second geometry, a triangle, once. Faces come in node order.
TEST(ColladaReader, EveryMeshOfEveryNode) {
  TempDir dir;
  const std::string geometries = kTetrahedron + triangle_geometry("tri", "0 0 -9  1 0 -9  0 1 -9", 3, "0 1 2", 1);
  const std::string nodes =
      "    <node id=\"a\"><instance_geometry url=\"#tet\"/></node>\n"
      "    <node id=\"b\"><matrix>1 0 0 5  0 1 0 0  0 0 1 0  0 0 0 1</matrix><instance_geometry url=\"#tet\"/></node>\n"
      "    <node id=\"c\"><instance_geometry url=\"#tri\"/></node>\n";
  const ProxyMesh mesh = read_proxy_mesh(dir.write("scene.dae", collada(geometries, nodes)));
  ASSERT_EQ(mesh.triangles.size(), 9u);
  EXPECT_EQ(mesh.positions.size(), 11u);
  EXPECT_EQ(mesh.corner_position(4, 0), glm::dvec3(5, 0, 0));  // the second tetrahedron's first corner
  EXPECT_EQ(mesh.corner_position(8, 0), glm::dvec3(0, 0, -9));
}

// A mirroring node (scale −1 along x) turns the faces' corners around, so the mesh still faces out.
TEST(ColladaReader, MirroringNodeKeepsTheFacesOutward) {
  TempDir dir;
  const std::string nodes = "    <node id=\"m\"><scale>-1 1 1</scale><instance_geometry url=\"#tet\"/></node>\n";
  const ProxyMesh mesh = read_proxy_mesh(dir.write("mirror.dae", collada(kTetrahedron, nodes)));
  expect_positions(mesh, {{-1, 0, 0}, {0, 0, 0}, {0, 0, 1}, {0, 1, 0}}, 0.0);
  EXPECT_TRUE(faces_outward(mesh));
}

// A <polylist> with a quad and a triangle, normals and UVs per corner, reads as the OBJ of the same
// polygons does: the quad cut along its shorter diagonal, the same positions, UVs and normals.
TEST(ColladaReader, PolylistReadsAsTheSameObj) {
  TempDir dir;
  const std::string geometry =
      "    <geometry id=\"q\"><mesh>\n"
      "      <source id=\"p\"><float_array id=\"pa\" count=\"15\">0 0 0 2 0 0 3 1 0 0 1 0 1 -1 0</float_array>\n"
      "        <technique_common><accessor source=\"#pa\" count=\"5\" stride=\"3\"><param name=\"X\" type=\"float\"/>"
      "<param name=\"Y\" type=\"float\"/><param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
      "      <source id=\"n\"><float_array id=\"na\" count=\"6\">0 0 2 0 0.6 0.8</float_array>\n"
      "        <technique_common><accessor source=\"#na\" count=\"2\" stride=\"3\"><param name=\"X\" type=\"float\"/>"
      "<param name=\"Y\" type=\"float\"/><param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
      "      <source id=\"t\"><float_array id=\"ta\" count=\"10\">0 0 0.5 0 0.75 0.25 0 0.25 0.25 0.125</float_array>\n"
      "        <technique_common><accessor source=\"#ta\" count=\"5\" stride=\"2\"><param name=\"S\" type=\"float\"/>"
      "<param name=\"T\" type=\"float\"/></accessor></technique_common></source>\n"
      "      <vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"
      "      <polylist count=\"2\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>"
      "<input semantic=\"NORMAL\" source=\"#n\" offset=\"1\"/><input semantic=\"TEXCOORD\" source=\"#t\" offset=\"2\" set=\"0\"/>\n"
      "        <vcount>4 3</vcount><p>0 0 0  1 0 1  2 1 2  3 0 3   0 0 0  4 1 4  1 0 1</p></polylist>\n"
      "    </mesh></geometry>\n";
  const ProxyMesh dae = read_proxy_mesh(dir.write("q.dae", collada(geometry, "    <node id=\"x\"><instance_geometry url=\"#q\"/></node>\n")));
  const ProxyMesh obj = read_proxy_mesh(dir.write("q.obj",
      "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 0 1 0\nv 1 -1 0\n"
      "vn 0 0 2\nvn 0 0.6 0.8\n"
      "vt 0 0\nvt 0.5 0\nvt 0.75 0.25\nvt 0 0.25\nvt 0.25 0.125\n"
      "f 1/1/1 2/2/1 3/3/2 4/4/1\nf 1/1/1 5/5/2 2/2/1\n"));
  ASSERT_EQ(dae.triangles.size(), 3u);
  ASSERT_TRUE(dae.has_uvs());
  ASSERT_TRUE(dae.has_normals());
  ASSERT_EQ(obj.triangles.size(), 3u);
  for (std::size_t t = 0; t < 3; ++t)
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(dae.corner_position(t, c), obj.corner_position(t, c)) << t << " " << c;
      EXPECT_EQ(dae.corner_uv(t, c), obj.corner_uv(t, c)) << t << " " << c;
      EXPECT_LT(glm::length(dae.corner_normal(t, c) - obj.corner_normal(t, c)), 1e-7) << t << " " << c;  // floats
    }
  EXPECT_EQ(dae.positions.size(), obj.positions.size());
}

// A compartment as cellPACK's database writes one (Cinema 4D's exporter: centimetre unit, Y_UP, a
// <polylist> with VERTEX and NORMAL offsets, a node of identity translate/rotate/scale): the
// icosahedron of HIV1_envelope_Pack_145_0_2_0.dae's first 12 vertices, radius 725 Å. It loads at
// that size, 20 faces as its <polylist count> says. (Written here, not copied: mesh_reader.hpp.)
TEST(ColladaReader, CellpackStyleEnvelopeLoadsInAngstromAtItsSize) {
  TempDir dir;
  const std::string a = "381.155", b = "616.722";
  const std::string positions = "0 " + a + " " + b + " 0 -" + a + " " + b + " " + b + " 0 " + a + " " + b + " 0 -" + a +
                                " 0 " + a + " -" + b + " 0 -" + a + " -" + b + " -" + b + " 0 -" + a + " -" + b + " 0 " +
                                a + " " + a + " " + b + " -0 -" + a + " " + b + " -0 -" + a + " -" + b + " -0 " + a + " -" +
                                b + " -0";
  const std::string faces = "0 1 2 0 7 1 0 2 8 0 9 7 0 8 9 1 11 2 1 7 10 1 10 11 2 3 8 2 11 3 3 5 4 3 4 8 3 11 5 4 5 6 "
                            "4 6 9 4 9 8 5 10 6 5 11 10 6 7 9 6 10 7";
  std::string p;  // VERTEX and NORMAL (offset 1: the vertex's own direction) per corner
  for (std::size_t at = 0; at < faces.size();) {
    const std::size_t end = std::min(faces.find(' ', at), faces.size());
    p += faces.substr(at, end - at) + " " + faces.substr(at, end - at) + " ";
    at = end + 1;
  }
  const std::string geometry =
      "    <geometry id=\"ID7\"><mesh>\n"
      "      <source id=\"ID8\"><float_array id=\"ID9\" count=\"36\">" + positions + "</float_array>\n"
      "        <technique_common><accessor source=\"#ID9\" count=\"12\" stride=\"3\"><param name=\"X\" type=\"float\"/>"
      "<param name=\"Y\" type=\"float\"/><param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
      "      <vertices id=\"ID10\"><input semantic=\"POSITION\" source=\"#ID8\"/></vertices>\n"
      "      <polylist count=\"20\" material=\"Material1\"><input semantic=\"VERTEX\" source=\"#ID10\" offset=\"0\"/>"
      "<input semantic=\"NORMAL\" source=\"#ID8\" offset=\"1\"/>\n"
      "        <vcount>" + [] { std::string v; for (int k = 0; k < 20; ++k) v += "3 "; return v; }() + "</vcount><p>" + p +
      "</p></polylist>\n    </mesh></geometry>\n";
  const std::string node =
      "    <node id=\"ID6\" name=\"HIV1_envelope_Pack_145_0_2_0\"><translate sid=\"translate\">0 0 -0</translate>"
      "<rotate sid=\"rotateY\">0 1 0 -0</rotate><rotate sid=\"rotateX\">1 0 0 0</rotate>"
      "<rotate sid=\"rotateZ\">0 0 1 -0</rotate><scale sid=\"scale\">1 1 1</scale><instance_geometry url=\"#ID7\"/></node>\n";
  const ProxyMesh mesh = read_proxy_mesh(dir.write("envelope.dae", collada(geometry, node, "0.01", "Y_UP")));
  EXPECT_EQ(mesh.triangles.size(), 20u);
  EXPECT_EQ(mesh.positions.size(), 12u);
  for (const glm::dvec3& v : mesh.positions) EXPECT_NEAR(glm::length(v), 725.0, 1e-3);
  EXPECT_NEAR(largest_side(mesh), 2 * 616.722, 1e-4);
  EXPECT_TRUE(faces_outward(mesh));
  ASSERT_TRUE(mesh.has_normals());  // the file's: each the vertex's direction
  EXPECT_LT(glm::length(mesh.corner_normal(0, 0) - glm::normalize(mesh.corner_position(0, 0))), 1e-6);
}

// What Assimp refuses, and what is refused before Assimp reads it, as InputErrors naming the file
// (mesh_reader.hpp). Nothing may be printed along the way.
TEST(ColladaReader, HostileFilesAreInputErrorsAndNothingIsPrinted) {
  TempDir dir;
  const std::string node = "    <node id=\"n\"><instance_geometry url=\"#t\"/></node>\n";
  const std::string good = collada(triangle_geometry("t", "0 0 0 1 0 0 0 1 0", 3, "0 1 2", 1), node);
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  expect_input_error(dir.write("malformed.dae", "<COLLADA><asset><unit meter=\"1\"></asset>"), "", "malformed XML");
  expect_input_error(dir.write("empty.dae", ""), "", "empty");
  expect_input_error(dir.write("not-xml.dae", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), "", "malformed XML");
  expect_input_error(dir.write("truncated.dae", good.substr(0, good.size() / 2)), "", "malformed XML");
  expect_input_error(dir.write("no-geometry.dae", collada("", "    <node id=\"n\"/>\n")), "", "no faces");
  expect_input_error(dir.write("range.dae", collada(triangle_geometry("t", "0 0 0 1 0 0 0 1 0", 3, "0 1 7", 1), node)), "",
                     "Invalid data index (7/3)");
  expect_input_error(dir.write("nan.dae", collada(triangle_geometry("t", "0 0 0 nan 0 0 0 1 0", 3, "0 1 2", 1), node)),
                     "vertex 1", "finite");
  expect_input_error(dir.write("repeat.dae", collada(triangle_geometry("t", "0 0 0 1 0 0 0 1 0", 3, "0 1 0", 1), node)),
                     "face 0", "repeated vertex");
  std::string billion = good;
  billion.replace(billion.find("<triangles count=\"1\""), 20, "<triangles count=\"999999999\"");
  expect_input_error(dir.write("billion.dae", billion), "line 9, <triangles>", "more than the file's size");
  std::string hex = good;
  hex.replace(hex.find("count=\"9\""), 9, "count=\"0x9\"");
  expect_input_error(dir.write("hex.dae", hex), "line 6, <float_array>", "not a decimal whole number");
  std::string wide = good;
  wide.replace(wide.find("offset=\"0\""), 10, "offset=\"40\"");
  expect_input_error(dir.write("offset.dae", wide), "line 9, <input>", "at most 31");
  // Assimp 5.2 would loop on "1!2" (growing its index list until memory runs out): found by the fuzzer.
  expect_input_error(dir.write("bang.dae", collada(triangle_geometry("t", "0 0 0 1 0 0 0 1 0", 3, "0 1!2", 1), node)),
                     "line 9, <p>", "holds '!'");
  expect_input_error(dir.write("cdata.dae", collada(triangle_geometry("t", "0 0 0 1 0 0 0 1 0", 3, "<![CDATA[0 1 2]]>", 1), node)),
                     "line 9, <p>", "holds '<'");
  // Debian's Assimp aborts (an assertion) on primitives whose count disagrees with their <p>s: found by the fuzzer.
  std::string no_p = good;
  no_p.replace(no_p.find("<p>0 1 2</p>"), 12, "");
  expect_input_error(dir.write("no-p.dae", no_p), "line 9, <triangles>", "count=\"1\" with 0 <p>");
  expect_input_error(dir.write("zip.dae", std::string("PK\x03\x04", 4) + good), "byte 2", "not XML text");
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

// No import process is left running or unreaped (a zombie) once the reader has returned or thrown.
void expect_no_child_processes() {
  errno = 0;
  EXPECT_EQ(::waitpid(-1, nullptr, WNOHANG), -1);
  EXPECT_EQ(errno, ECHILD);
}

// The file that made Assimp 5.2 dereference null, as the fuzzer found it (a misspelt
// <float_array> count, docs/tests.md): Assimp crashes in its own process, and
// this one gets an InputError naming the file and the signal, then reads the next file as before.
TEST(ColladaReader, AssimpCrashingIsAnInputErrorAndThisProcessGoesOn) {
  TempDir dir;
  const std::string node = "    <node id=\"n\"><instance_geometry url=\"#tet\"/></node>\n";
  std::string misspelt = collada(kTetrahedron, node);
  misspelt.replace(misspelt.find("count=\"12\""), 5, "coqnt");
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  expect_input_error(dir.write("misspelt-count.dae", misspelt), "", "Assimp stopped on this file (signal 11: SIGSEGV");
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  expect_no_child_processes();
  EXPECT_EQ(read_proxy_mesh(dir.write("tet.dae", collada(kTetrahedron, node))).triangles.size(), 4u);
  expect_no_child_processes();
}

// A grid of `side` × `side` squares as triangles, some 30 bytes of text per triangle.
std::string large_grid(int side) {
  std::string positions, triangles;
  for (int y = 0; y <= side; ++y)
    for (int x = 0; x <= side; ++x) positions += std::to_string(x) + " " + std::to_string(y) + " 0 ";
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const int a = y * (side + 1) + x, b = a + 1, c = a + side + 1, d = c + 1;
      triangles += std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(d) + " " + std::to_string(a) + " " +
                   std::to_string(d) + " " + std::to_string(c) + " ";
    }
  return collada(triangle_geometry("grid", positions, (side + 1) * (side + 1), triangles, 2 * side * side),
                 "    <node id=\"n\"><instance_geometry url=\"#grid\"/></node>\n");
}

void expect_import_refused(const std::string& text, const ColladaImportLimits& limits, const std::string& rule_part) {
  try {
    read_collada_soup(text, "limited.dae", limits);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "limited.dae");
    EXPECT_NE(e.rule().find(rule_part), std::string::npos) << e.what();
  }
}

// The time limit (60 s in nanobake, shortened here): an import still running when it passes is
// stopped and said to be. (No file Assimp loops on gets past check(); a large one stands in.)
TEST(ColladaReader, ImportOverTheTimeLimitIsStoppedAndSaidToBe) {
  const std::string grid = large_grid(300);  // 180,000 triangles, 5 MB
  const auto start = std::chrono::steady_clock::now();
  expect_import_refused(grid, {.time = std::chrono::milliseconds(20)}, "within 0.02 s (the time limit); its process was stopped (SIGKILL)");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  expect_no_child_processes();
  EXPECT_EQ(read_collada_soup(grid, "limited.dae").face_ends.size(), 180'000u);  // within the default limit
  expect_no_child_processes();
}

// The address space limit: an import that needs more ends as an InputError (Assimp's allocation
// failing; pugixml's out of memory comes back as "malformed XML", hence the note), not as this
// process running out of memory.
TEST(ColladaReader, ImportOverTheAddressSpaceLimitIsAnInputError) {
  const std::string grid = large_grid(300);
  expect_import_refused(grid, {.address_space = 8 << 20, .address_space_per_byte = 1},
                        "MiB of the 8 MiB of address space it may add: the failure may be an allocation that did not fit");
  expect_no_child_processes();
}

// parse_proxy_mesh (bytes in memory) is what read_proxy_mesh does with the file's bytes.
TEST(ColladaReader, ParsesBytesInMemory) {
  const std::string text = collada(kTetrahedron, "    <node id=\"n\"><instance_geometry url=\"#tet\"/></node>\n");
  const ProxyMesh mesh = parse_proxy_mesh(std::as_bytes(std::span(text.data(), text.size())), MeshFormat::collada, "label.dae");
  EXPECT_EQ(mesh.triangles.size(), 4u);
  try {
    const std::string bad = "<COLLADA>";
    parse_proxy_mesh(std::as_bytes(std::span(bad.data(), bad.size())), MeshFormat::collada, "label.dae");
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "label.dae");
  }
}

}  // namespace
}  // namespace nano::mesh
