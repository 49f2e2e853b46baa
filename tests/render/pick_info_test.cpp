// describe_hit on the hand-built package of tests/oracle (every record known), against the
// records it was built from; hostile hits give an error, never a crash. The bundled virion is
// checked against gemmi by pick_gemmi.py.
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "runtime/render/pick_info.hpp"
#include "tests/oracle/hand_scene.hpp"
#include "tests/format/sample_scene.hpp"
#include "tests/oracle/test_package.hpp"

namespace {

using namespace nano;
using explicit_test::TestPackage;
using nlohmann::json;

// The hand scene with names: molecule types "lysine bit" / "iron" from "hand.pdb", compartments
// "flat", "" (no name) and "core"; atom 2 gets an insertion code and an alternate location.
format::test::SampleScene named_scene() {
  format::test::SampleScene s = explicit_test::hand_scene();
  const auto add = [&](const std::string& text) {
    const auto offset = std::uint32_t(s.strings.size());
    s.strings += text;
    return std::pair{offset, std::uint32_t(text.size())};
  };
  std::tie(s.molecules[0].name_offset, s.molecules[0].name_length) = add("lysine bit");
  std::tie(s.molecules[1].name_offset, s.molecules[1].name_length) = add("iron");
  for (auto& m : s.molecules) std::tie(m.source_offset, m.source_length) = add("hand.pdb");
  std::tie(s.compartments[0].name_offset, s.compartments[0].name_length) = add("flat");
  std::tie(s.compartments[2].name_offset, s.compartments[2].name_length) = add("core");
  s.atom_info[2].insertion_code = 'A';
  s.atom_info[2].alt_location = 'B';
  return s;
}

gpu::PixelHit membrane_hit(std::uint32_t ci, std::uint32_t triangle, int a, int b, std::uint32_t instance, std::uint32_t atom) {
  gpu::PixelHit h{};
  h.depth = 12.5f;
  h.compartment_instance = ci;
  h.element = triangle;
  h.kind = 0;
  h.cell = glm::ivec4(a, b, 0, 0);
  h.instance = instance;
  h.atom = atom;
  h.copy_number_lo = 7;
  h.copy_number_hi = 1;
  return h;
}

gpu::PixelHit core_hit(glm::ivec3 ijk, std::uint32_t instance, std::uint32_t atom) {
  gpu::PixelHit h = membrane_hit(3, 0, 0, 0, instance, atom);  // instance 3 is the core compartment
  h.kind = 1;
  h.cell = glm::ivec4(ijk, 0);
  h.element = std::uint32_t(ijk.x + 3 * (ijk.y + 2 * ijk.z));  // grid 3 × 2 × 2
  return h;
}

class PickInfo : public ::testing::Test {
protected:
  format::test::SampleScene scene = named_scene();
  TestPackage test{scene};
  const format::Package& package = test.package;
};

TEST_F(PickInfo, BackgroundIsNoHit) {
  gpu::PixelHit h;
  std::memset(&h, 0xFF, sizeof h);
  h.depth = std::numeric_limits<float>::infinity();
  EXPECT_EQ(render::describe_hit(package, h), json({{"hit", false}}));
  EXPECT_EQ(render::describe_hit_text(render::describe_hit(package, h)), "background");
}

TEST_F(PickInfo, MembraneHitNamesEverything) {
  // Cell (0, 0) of the 2 × 2 checkerboard recipe is Wang square 0; its molecule 0 is of type 0.
  const json d = render::describe_hit(package, membrane_hit(0, 1, 0, 0, 0, 1));
  const json expected = {
      {"hit", true},
      {"depth", 12.5},
      {"atom",
       {{"index", 1}, {"index_in_molecule", 1}, {"name", "CA"}, {"element", "C"}, {"chain", "A"}, {"residue_name", "LYS"},
        {"residue_number", 42}, {"position", {1.5, 0.0, 0.0}}, {"radius", double(1.2f)}}},
      {"molecule", {{"type", 0}, {"name", "lysine bit"}, {"source", "hand.pdb"}}},
      {"compartment_instance", {{"index", 0}, {"compartment", 0}, {"name", "flat"}}},
      {"placement",
       {{"kind", "membrane"}, {"triangle", 1}, {"tile", {0, 0}}, {"wang_square", 0}, {"copy", 0},
        {"copy_number", (std::uint64_t(1) << 32) + 7}}}};
  EXPECT_EQ(d, expected) << d.dump(1);
  const std::string text = render::describe_hit_text(d);
  for (const char* part : {"atom CA (C) of LYS 42, chain A", "molecule lysine bit (type 0, from hand.pdb)",
                           "compartment flat, instance 0; membrane, triangle 1, tile (0, 0), copy 0", "copy number 4294967303"})
    EXPECT_NE(text.find(part), std::string::npos) << part << " in\n" << text;
}

TEST_F(PickInfo, InsertionCodeAndAltLocationOnlyWhenPresent) {
  const json with = render::describe_hit(package, membrane_hit(0, 0, 0, 0, 0, 2));
  EXPECT_EQ(with["atom"]["insertion_code"], "A");
  EXPECT_EQ(with["atom"]["alt_location"], "B");
  EXPECT_NE(render::describe_hit_text(with).find("of LYS 43A, chain A, alt. location B"), std::string::npos);
  const json without = render::describe_hit(package, membrane_hit(0, 0, 0, 0, 0, 0));
  EXPECT_FALSE(without["atom"].contains("insertion_code"));
  EXPECT_FALSE(without["atom"].contains("alt_location"));
}

TEST_F(PickInfo, UnnamedCompartmentAndNegativeCellsWrap) {
  // Compartment 1 has no name; cell (−1, −2) wraps to recipe slot (1, 0): Wang square 1, whose one
  // molecule is of type 0.
  const json d = render::describe_hit(package, membrane_hit(1, 2, -1, -2, 0, 0));
  ASSERT_FALSE(d.contains("error")) << d.dump();
  EXPECT_EQ(d["compartment_instance"], json({{"index", 1}, {"compartment", 1}}));
  EXPECT_EQ(d["placement"]["wang_square"], 1);
  EXPECT_NE(render::describe_hit_text(d).find("compartment 1, instance 1"), std::string::npos);
}

TEST_F(PickInfo, CoreHit) {
  // Box (0, 0, 1) → recipe slot 0 → Wang cube 1, whose molecule 1 is of type 1 (atom 3, haem iron).
  const json d = render::describe_hit(package, core_hit({0, 0, 1}, 1, 3));
  ASSERT_FALSE(d.contains("error")) << d.dump();
  EXPECT_EQ(d["placement"], json({{"kind", "core"}, {"box", 6}, {"box_ijk", {0, 0, 1}}, {"wang_cube", 1}, {"copy", 1},
                                  {"copy_number", (std::uint64_t(1) << 32) + 7}}));
  EXPECT_EQ(d["atom"]["name"], "FE");
  EXPECT_EQ(d["atom"]["element"], "FE");
  EXPECT_EQ(d["atom"]["residue_name"], "HEM");
  EXPECT_EQ(d["molecule"]["name"], "iron");
  EXPECT_EQ(d["compartment_instance"]["name"], "core");
  EXPECT_NE(render::describe_hit_text(d).find("core, box (0, 0, 1), copy 1"), std::string::npos);
}

// A medium copy belongs to no instance: the format tests' sample package puts its one cube (whose
// molecule 0 is of type 0, atoms 0-2) in every box of an 8 × 8 × 8 region.
TEST(PickInfoMedium, MediumHitNamesItsBoxAndCube) {
  const explicit_test::TestPackage sample(format::test::make_sample_scene());
  gpu::PixelHit h{};
  h.depth = 5;
  h.compartment_instance = gpu::NANO_MEDIUM_OWNER;
  h.kind = gpu::NANO_KIND_MEDIUM;
  h.cell = glm::ivec4(1, 2, 3, 0);
  h.element = 1 + 8 * (2 + 8 * 3);
  h.instance = 0;
  h.atom = 1;
  h.copy_number_lo = 7;
  const json d = render::describe_hit(sample.package, h);
  ASSERT_FALSE(d.contains("error")) << d.dump();
  EXPECT_EQ(d["placement"], json({{"kind", "medium"}, {"box", 209}, {"box_ijk", {1, 2, 3}}, {"wang_cube", 0}, {"copy", 0},
                                  {"copy_number", 7}}));
  EXPECT_EQ(d["compartment_instance"], json({{"medium", true}}));
  EXPECT_NE(render::describe_hit_text(d).find("the medium, between the compartments; medium, box (1, 2, 3), copy 0"),
            std::string::npos) << render::describe_hit_text(d);
  h.cell.x = 8;
  EXPECT_NE(render::describe_hit(sample.package, h).value("error", "").find("lies outside the medium's region"), std::string::npos);
  h.cell.x = 1, h.compartment_instance = 0;
  EXPECT_NE(render::describe_hit(sample.package, h).value("error", "").find("medium hit naming compartment instance 0"),
            std::string::npos);
}

// Every copy the analytic oracle knows describes without error and with its atom's own records.
TEST_F(PickInfo, EveryRealCopyDescribes) {
  const std::vector<explicit_test::Placement> placements = explicit_test::default_placements();
  std::size_t checked = 0;
  for (const auto& [key, atom] : explicit_test::expected_atoms(scene)) {
    gpu::PixelHit h = key.kind == 0 ? membrane_hit(key.compartment_instance, scene.meshes[placements[key.compartment_instance].compartment].first_triangle,
                                                   key.cell.x, key.cell.y, key.instance, key.atom)
                                    : core_hit(key.cell, key.instance, key.atom);
    const json d = render::describe_hit(package, h);
    ASSERT_FALSE(d.contains("error")) << d.dump();
    EXPECT_EQ(d["atom"]["name"], std::string(scene.atom_info[key.atom].atom_name, strnlen(scene.atom_info[key.atom].atom_name, 4)));
    EXPECT_EQ(d["atom"]["radius"], double(atom.radius));
    ++checked;
  }
  EXPECT_GT(checked, 100u);
}

TEST_F(PickInfo, HostileHitsAreErrorsNamingTheProblem) {
  const auto error_of = [&](const gpu::PixelHit& h) {
    const json d = render::describe_hit(package, h);
    EXPECT_EQ(d["hit"], true);
    EXPECT_EQ(render::describe_hit_text(d).rfind("invalid hit: ", 0), 0u);
    return d.value("error", std::string("(no error)"));
  };
  const gpu::PixelHit good = membrane_hit(0, 1, 0, 0, 0, 1);
  gpu::PixelHit h = good;
  h.atom = 4;
  EXPECT_NE(error_of(h).find("atom 4 is out of range: section atoms has 4 record(s)"), std::string::npos);
  h = good, h.compartment_instance = 4;
  EXPECT_NE(error_of(h).find("compartment instance 4 is out of range"), std::string::npos);
  h = good, h.kind = 2;  // a medium hit in a package without a medium
  EXPECT_NE(error_of(h).find("medium hit in a package without a medium"), std::string::npos);
  h = good, h.kind = 3;
  EXPECT_NE(error_of(h).find("kind 3 is neither 0 (membrane), 1 (core) nor 2 (medium)"), std::string::npos);
  h = good, h.element = 2;  // triangle 2 belongs to the mirrored square's mesh
  EXPECT_NE(error_of(h).find("triangle 2 is not one of the compartment's mesh"), std::string::npos);
  h = good, h.instance = 4;  // Wang square 0 holds 4 molecules
  EXPECT_NE(error_of(h).find("copy 4 is out of range: its Wang square holds 4"), std::string::npos);
  h = good, h.atom = 3;  // a type-1 atom in a type-0 copy
  EXPECT_NE(error_of(h).find("atom 3 belongs to molecule type 1 but the copy the ids name is of type 0"), std::string::npos);
  h = good, h.depth = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(error_of(h).find("depth"), std::string::npos);
  h = good, h.compartment_instance = 3;  // the core-only compartment
  EXPECT_NE(error_of(h).find("membrane hit in a compartment without a membrane"), std::string::npos);
  h = core_hit({0, 0, 1}, 1, 3), h.element = 5;
  EXPECT_NE(error_of(h).find("box index 5 is not the linear index of its (i, j, k)"), std::string::npos);
  h = core_hit({3, 0, 0}, 1, 3);
  EXPECT_NE(error_of(h).find("lies outside the core grid"), std::string::npos);
  h = core_hit({0, 0, 1}, 1, 3), h.compartment_instance = 0;
  EXPECT_NE(error_of(h).find("core hit in a compartment without a core grid"), std::string::npos);
}

TEST_F(PickInfo, RandomHitsNeverCrash) {
  std::mt19937 rng(5);
  const auto small = [&](std::uint32_t n) { return std::uint32_t(rng() % n) + (rng() % 8 == 0 ? 0xFFFFFFF0u : 0u); };
  std::size_t valid = 0;
  for (int i = 0; i < 20000; ++i) {
    gpu::PixelHit h{};
    h.depth = rng() % 16 == 0 ? -1.0f : float(rng() % 1000);
    h.compartment_instance = small(5);
    h.kind = small(3);
    h.element = small(14);
    h.cell = glm::ivec4(int(rng() % 9) - 4, int(rng() % 9) - 4, int(rng() % 5) - 2, int(rng()));
    h.instance = small(5);
    h.atom = small(5);
    const json d = render::describe_hit(package, h);
    ASSERT_EQ(d["hit"], true);
    if (!d.contains("error")) {
      ++valid;
      EXPECT_FALSE(render::describe_hit_text(d).empty());
    }
  }
  EXPECT_GT(valid, 20u);  // the generator also reaches real copies
}

}  // namespace
