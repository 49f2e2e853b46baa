// Unit tests of the renderer's host modules: Morton order, camera parsing, image files.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "runtime/render/camera_spec.hpp"
#include "runtime/render/image_io.hpp"
#include "runtime/render/kept_boxes.hpp"
#include "shared/render_scene.h"
#include "runtime/render/morton.hpp"
#include "tests/oracle/hand_scene.hpp"
#include "tests/scene/input_error_matchers.hpp"
#include "tests/oracle/test_package.hpp"

namespace {

using namespace nano::render;
using nano::Camera;
using nano::InputError;
using nano::scene::testing::expect_input_error;

TEST(MortonOrder, IsAPermutationThatKeepsNeighboursTogether) {
  // Boxes on a 16×16×16 lattice, shuffled: after sorting, consecutive boxes are mostly lattice
  // neighbours (the Z curve jumps rarely), and every index appears once.
  std::vector<VkAabbPositionsKHR> boxes;
  for (int z = 0; z < 16; ++z)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) boxes.push_back({float(x), float(y), float(z), x + 0.5f, y + 0.5f, z + 0.5f});
  std::mt19937 rng(7);
  std::shuffle(boxes.begin(), boxes.end(), rng);
  const std::vector<std::uint32_t> order = morton_order(boxes);
  ASSERT_EQ(order.size(), boxes.size());
  EXPECT_EQ(std::set<std::uint32_t>(order.begin(), order.end()).size(), boxes.size());
  int adjacent = 0;
  for (std::size_t i = 1; i < order.size(); ++i) {
    const auto& a = boxes[order[i - 1]];
    const auto& b = boxes[order[i]];
    adjacent += std::abs(a.minX - b.minX) + std::abs(a.minY - b.minY) + std::abs(a.minZ - b.minZ) == 1.0f;
  }
  EXPECT_GT(adjacent, int(0.45 * order.size()));  // a Z curve steps to a face neighbour about half the time
  // The shuffled input order itself almost never does.
  int adjacent_input = 0;
  for (std::size_t i = 1; i < boxes.size(); ++i)
    adjacent_input += std::abs(boxes[i - 1].minX - boxes[i].minX) + std::abs(boxes[i - 1].minY - boxes[i].minY) +
                          std::abs(boxes[i - 1].minZ - boxes[i].minZ) == 1.0f;
  EXPECT_LT(adjacent_input, int(0.05 * boxes.size()));
  EXPECT_TRUE(morton_order({}).empty());
}

TEST(Camera, ParsesKeysInAnyOrderAndKeepsTheRest) {
  Camera base;
  const Camera c = parse_camera("fov=30;pos=1,2,3;at=4,5,6", base, "--camera");
  EXPECT_EQ(c.position, glm::dvec3(1, 2, 3));
  EXPECT_EQ(c.look_at, glm::dvec3(4, 5, 6));
  EXPECT_EQ(c.up, base.up);
  EXPECT_EQ(c.fov_degrees, 30);
  const Camera again = parse_camera(c.to_string(), {}, "--camera");
  EXPECT_EQ(again.position, c.position);
  EXPECT_EQ(again.look_at, c.look_at);
  EXPECT_DOUBLE_EQ(again.fov_degrees, c.fov_degrees);
}

// to_string writes the --camera form; it reads back to the same doubles through the long keys, and
// through the aliases too, which mean exactly the same.
TEST(Camera, TextRoundTripsThroughTheLongKeysAndTheAliases) {
  Camera c;
  c.position = {0.1 + 0.2, -2.0, 3e7};
  c.look_at = {1.0 / 3.0, 0.0, -7.5};
  c.up = {0.2, 1.0, std::nextafter(0.0, 1.0)};
  c.fov_degrees = std::nextafter(45.0, 90.0);
  const std::string text = c.to_string();
  EXPECT_EQ(text.rfind("position=", 0), 0u) << text;
  for (const char* key : {";look_at=", ";up=", ";fov_degrees="}) EXPECT_NE(text.find(key), std::string::npos) << text;
  EXPECT_EQ(parse_camera(text, {}, "--camera"), c);
  EXPECT_EQ(parse_camera(text, Camera{{5, 5, 5}, {1, 1, 1}, {0, 0, 1}, 10}, "--camera"), c);  // nothing of the base is left
  std::string aliased = text;
  for (const auto& [word, alias] : {std::pair<std::string, std::string>{"position=", "pos="}, {"look_at=", "at="}, {"fov_degrees=", "fov="}})
    aliased.replace(aliased.find(word), word.size(), alias);
  EXPECT_EQ(aliased.rfind("pos=", 0), 0u) << aliased;
  EXPECT_EQ(parse_camera(aliased, {}, "--camera"), c);
  // Long keys and aliases mix.
  EXPECT_EQ(parse_camera("pos=1,2,3;look_at=4,5,6;fov_degrees=30", {}, "--camera"),
            parse_camera("position=1,2,3;at=4,5,6;fov=30", {}, "--camera"));
}

TEST(Camera, RefusesAKeyGivenTwice) {
  for (const char* twice : {"position=1,2,3;pos=1,2,3", "at=0,0,0;look_at=0,0,0", "fov=30;fov=30", "up=0,1,0;up=0,1,0"}) {
    try {
      (void)parse_camera(twice, {}, "--camera");
      ADD_FAILURE() << "accepted: " << twice;
    } catch (const InputError& e) {
      EXPECT_NE(e.rule().find("repeats"), std::string::npos) << e.what();
    }
  }
}

TEST(Camera, RejectsWhatCannotBeACameraNamingTheOption) {
  for (const char* wrong : {"pos=1,2", "pos=1,2,3,4", "zoom=2", "eye=1,2,3" /* no other spellings than the aliases */,
                            "target=1,2,3", "position=0,0,0;look_at=0,0,0", "fov_degrees=0", "pos=0,0,0;at=0,0,0",
                            "pos=0,0,5;at=0,0,0;up=0,0,1" /* up ∥ view */, "fov=180", "pos=nan,0,0", "fov=abc"}) {
    const InputError e = expect_input_error([&] { (void)parse_camera(wrong, {}, "--camera"); });
    EXPECT_EQ(e.file(), "--camera") << wrong;
    EXPECT_EQ(e.rule().rfind("camera: ", 0), 0u) << e.what();
  }
}

// A spec read from a file (a script line, a path's keyframe) names the file and the place in it.
TEST(Camera, ErrorNamesTheFileAndPlaceItCameFrom) {
  const InputError e = expect_input_error([] { (void)parse_camera("zoom=2", {}, {"tour.nvs", "line 12"}); });
  EXPECT_STREQ(e.what(), "tour.nvs:line 12: camera: unknown key 'zoom' (position, look_at, up, fov_degrees; aliases pos, at, fov)");
}

TEST(Camera, PixelRaysFollowTheDocumentedConvention) {
  // fov 90°, 2×2 pixels: pixel (0, 0) is top-left, so its ray goes left (−right) and up.
  Camera c;
  c.position = {0, 0, 0}, c.look_at = {0, 0, -1}, c.up = {0, 1, 0}, c.fov_degrees = 90;
  const nano::gpu::Camera cam = c.to_gpu(2, 2);
  const glm::vec3 d = nano::gpu::camera_ray_direction(cam, 0, 0);
  EXPECT_NEAR(d.x, -1 / std::sqrt(6.0), 1e-6);  // right = forward × up = (1, 0, 0); ndc = (−½, ½)
  EXPECT_NEAR(d.y, 1 / std::sqrt(6.0), 1e-6);
  EXPECT_NEAR(d.z, -2 / std::sqrt(6.0), 1e-6);
}

std::filesystem::path temp_path(const char* name) {
  return std::filesystem::temp_directory_path() / (std::string("nano_render_test_") + name);
}

TEST(ImageFiles, PngRoundTripsEveryChannel) {
  const std::uint32_t w = 5, h = 3;
  std::vector<std::uint32_t> rgba(w * h);
  for (std::uint32_t i = 0; i < rgba.size(); ++i) rgba[i] = 0x01020304u * (i + 1) ^ 0xA5000000u;
  const auto path = temp_path("roundtrip.png");
  write_png(path, w, h, rgba);
  std::uint32_t rw = 0, rh = 0;
  EXPECT_EQ(read_png(path, rw, rh), rgba);
  EXPECT_EQ(rw, w);
  EXPECT_EQ(rh, h);
  std::filesystem::remove(path);
  EXPECT_THROW(write_png(path, 4, 4, rgba), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(ImageFiles, ReadingAGarbledPngNamesTheFile) {
  const auto path = temp_path("garbled.png");
  std::ofstream(path, std::ios::binary) << "\x89PNG\r\n\x1a\nthis is not a PNG";
  std::uint32_t w, h;
  try {
    read_png(path, w, h);
    ADD_FAILURE() << "no error";
  } catch (const nano::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

TEST(ImageFiles, PfmStoresRowsBottomUpLittleEndian) {
  std::vector<nano::gpu::PixelHit> hits(2 * 2);
  for (std::size_t i = 0; i < hits.size(); ++i) hits[i].depth = float(i + 1);
  hits[1].depth = INFINITY;
  const auto path = temp_path("depth.pfm");
  write_depth_pfm(path, 2, 2, hits);
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string header = "Pf\n2 2\n-1.0\n";
  ASSERT_EQ(bytes.size(), header.size() + 16);
  EXPECT_EQ(bytes.substr(0, header.size()), header);
  float v[4];
  std::memcpy(v, bytes.data() + header.size(), 16);
  // First stored row = bottom image row (pixels 2, 3), then the top row (0, 1).
  EXPECT_EQ(v[0], 3.0f);
  EXPECT_EQ(v[1], 4.0f);
  EXPECT_EQ(v[2], 1.0f);
  EXPECT_TRUE(std::isinf(v[3]));
  std::filesystem::remove(path);
}

// A packed kept box holds the box it was made from, one grid step (3B/31) at most larger on each side,
// decoded in float as the shader does, for box edges from 1 Å to 10⁴ Å and corners on grid points.
TEST(KeptBoxes, PackingHoldsTheBoxWithinOneStep) {
  std::mt19937 rng(30);
  for (const float B : {1.0f, 20.0f, 191.3f, 1e4f}) {
    const double step = 3.0 * B / 31.0;
    std::uniform_real_distribution<double> at(-B, 2.0 * B);
    for (int n = 0; n < 2000; ++n) {
      glm::dvec3 lo(at(rng), at(rng), at(rng)), hi(at(rng), at(rng), at(rng));
      if (n % 5 == 0) lo.x = -B + step * (n % 31), hi.x = -B + step * (n % 31 + 1);  // exactly on grid points
      const glm::dvec3 a = glm::min(lo, hi), b = glm::max(lo, hi);
      glm::vec3 plo, phi;
      ASSERT_TRUE(nano::gpu::kept_box_unpack(kept_box_pack(a, b, B), B, plo, phi));
      for (int k = 0; k < 3; ++k) {
        ASSERT_LE(double(plo[k]), a[k]) << B << " " << n;
        ASSERT_GE(double(phi[k]), b[k]) << B << " " << n;
        ASSERT_GT(double(plo[k]), a[k] - step * 1.0001) << B << " " << n;
        ASSERT_LT(double(phi[k]), b[k] + step * 1.0001) << B << " " << n;
      }
    }
  }
  glm::vec3 lo, hi;
  EXPECT_FALSE(nano::gpu::kept_box_unpack(0u, 20.0f, lo, hi));  // keeps nothing
}

// Against the hand scene's plane geometry (tests/oracle/hand_scene.hpp): every atom of a copy a
// BOUNDARY box keeps lies in that box's kept box, a box whose mask keeps nothing has none, and a box
// that drops a molecule has a kept box smaller than its cube's whole reach.
TEST(KeptBoxes, HoldEveryKeptAtomAndNothingForAnEmptyMask) {
  const std::vector<nano::explicit_test::Placement> alone{{2, {0, 0, 1}, 0, {0, 0, 0}}};  // the core, untransformed
  const nano::format::test::SampleScene scene = nano::explicit_test::hand_scene(alone);
  const nano::explicit_test::TestPackage pkg(scene);
  const nano::format::PackageView view(pkg.package);
  const std::vector<double> radii = view.atom_bounding_radii();
  const std::vector<std::uint32_t> kept = kept_boxes(view, radii);
  ASSERT_EQ(kept.size(), view.boundary_boxes.size());
  ASSERT_GT(kept.size(), 0u);
  const nano::gpu::Compartment& c = view.compartments[2];
  const auto record_of = [&](std::uint32_t box) {
    for (std::uint32_t r = c.core_masks.x; r < c.core_masks.x + c.core_masks.y; ++r)
      if (view.boundary_boxes[r].box == box) return int(r);
    return -1;
  };
  std::set<int> holding;
  for (const auto& [key, atom] : nano::explicit_test::expected_atoms(scene, alone)) {
    if (key.kind != 1) continue;
    const std::uint32_t box = std::uint32_t(key.cell.x + c.grid_dims.x * (key.cell.y + c.grid_dims.y * key.cell.z));
    const int r = record_of(box);
    if (r < 0) continue;  // an INSIDE box: every molecule kept, no record
    holding.insert(r);
    const glm::dvec3 box_min = glm::dvec3(c.grid_min) + double(c.grid_min.w) * glm::dvec3(key.cell);
    glm::vec3 lo, hi;
    ASSERT_TRUE(nano::gpu::kept_box_unpack(kept[r], c.grid_min.w, lo, hi)) << "box " << box;
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE(box_min[a] + lo[a], atom.position[a] - atom.radius) << "box " << box << " axis " << a;
      EXPECT_GE(box_min[a] + hi[a], atom.position[a] + atom.radius) << "box " << box << " axis " << a;
    }
  }
  bool smaller = false;
  for (std::uint32_t r = c.core_masks.x; r < c.core_masks.x + c.core_masks.y; ++r) {
    if (!holding.count(int(r))) {
      EXPECT_EQ(kept[r], 0u) << "record " << r << " keeps no atom but has a kept box";
      continue;
    }
    // The cube's whole reach: every molecule of the box's cube, kept or not, widened as the mLAS's.
    const nano::gpu::BoundaryBox& b = view.boundary_boxes[r];
    const nano::gpu::Tile3D& cube = view.tiles3d[b.box % c.grid_dims.x % 2 == 0 ? 1 : 2];  // the hand recipe [1, 2] along x
    glm::dvec3 whole_lo(INFINITY), whole_hi(-INFINITY);
    for (std::uint32_t m = 0; m < cube.instance_count; ++m) {
      const nano::gpu::MoleculeInstance& inst = view.instances[cube.first_instance + m];
      const double e = radii[inst.molecule_type] + 0.01;
      whole_lo = glm::min(whole_lo, glm::dvec3(inst.position) - e), whole_hi = glm::max(whole_hi, glm::dvec3(inst.position) + e);
    }
    glm::vec3 lo, hi;
    nano::gpu::kept_box_unpack(kept[r], c.grid_min.w, lo, hi);
    for (int a = 0; a < 3; ++a) smaller = smaller || lo[a] > whole_lo[a] + 1.0 || hi[a] < whole_hi[a] - 1.0;
  }
  EXPECT_TRUE(smaller) << "no kept box is smaller than its cube's reach: the masks would prune nothing";
}

}  // namespace
