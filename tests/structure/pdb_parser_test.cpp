#include "bake/structure/pdb_parser.hpp"

#include "tests/structure/structure_test_support.hpp"

namespace nano::structure {
namespace {

using testing::expect_input_error;
using testing::pdb_line;
using testing::PdbAtomLine;

TEST(PdbParser, ReadsEveryFixedColumnField) {
  const std::string text = "HEADER    TEST\n" + pdb_line({.name = " CA ", .residue = "GLY", .chain = 'B', .residue_number = -3,
                                                          .insertion_code = 'A', .x = 1.5, .y = -2.25, .z = 1000.125,
                                                          .occupancy = 0.5, .element = "C"}) +
                           pdb_line({.record = "HETATM", .name = "FE  ", .residue = "HEM", .chain = 'C', .residue_number = 150,
                                     .x = -0.001, .element = "FE"});
  const ParsedStructure parsed = parse_pdb(text, "t.pdb");
  ASSERT_EQ(parsed.atoms.size(), 2u);
  EXPECT_EQ(parsed.model_count, 1);
  const Atom& a = parsed.atoms[0];
  EXPECT_EQ(a.atom_name, "CA");
  EXPECT_EQ(a.residue_name, "GLY");
  EXPECT_EQ(a.chain, "B");
  EXPECT_EQ(a.residue_number, -3);
  EXPECT_EQ(a.insertion_code, "A");
  EXPECT_DOUBLE_EQ(a.position.x, 1.5);
  EXPECT_DOUBLE_EQ(a.position.y, -2.25);
  EXPECT_DOUBLE_EQ(a.position.z, 1000.125);
  EXPECT_DOUBLE_EQ(a.occupancy, 0.5);
  EXPECT_EQ(a.element, "C");
  EXPECT_FALSE(a.hetatm);
  EXPECT_EQ(a.line, 2u);
  const Atom& fe = parsed.atoms[1];
  EXPECT_TRUE(fe.hetatm);
  EXPECT_EQ(fe.element, "Fe");
  EXPECT_EQ(fe.insertion_code, "");
  EXPECT_DOUBLE_EQ(fe.position.x, -0.001);
}

TEST(PdbParser, AcceptsFourCharacterResidueNamesInColumns18To21) {
  std::string line = pdb_line({.record = "HETATM", .name = " C1 ", .residue = "POP", .chain = 'L', .element = "C"});
  line[20] = 'C';  // column 21
  const ParsedStructure parsed = parse_pdb(line, "t.pdb");
  EXPECT_EQ(parsed.atoms[0].residue_name, "POPC");
  EXPECT_EQ(parsed.atoms[0].chain, "L");
}

TEST(PdbParser, DecodesHybrid36ResidueNumbers) {
  std::string line = pdb_line({});
  line.replace(22, 4, "A001");  // columns 23-26: 10000 + 1
  EXPECT_EQ(parse_pdb(line, "t.pdb").atoms[0].residue_number, 10001);
}

TEST(PdbParser, InfersElementsFromAtomNamesWhenColumns77To78AreBlank) {
  const std::string text = pdb_line({.name = " CA ", .element = ""}) +
                           pdb_line({.record = "HETATM", .name = "CA  ", .residue = " CA", .residue_number = 2, .element = ""}) +
                           pdb_line({.name = "1HB ", .residue_number = 3, .element = ""}) +
                           pdb_line({.name = "HG21", .residue = "THR", .residue_number = 4, .element = ""}) +
                           pdb_line({.name = " OG1", .residue = "THR", .residue_number = 4, .element = ""});
  const ParsedStructure parsed = parse_pdb(text, "t.pdb");
  ASSERT_EQ(parsed.atoms.size(), 5u);
  EXPECT_EQ(parsed.atoms[0].element, "C");   // carbon alpha
  EXPECT_EQ(parsed.atoms[1].element, "Ca");  // calcium ion
  EXPECT_EQ(parsed.atoms[2].element, "H");   // old-style hydrogen name
  EXPECT_EQ(parsed.atoms[3].element, "H");   // 4-character hydrogen name, not mercury
  EXPECT_EQ(parsed.atoms[4].element, "O");
}

TEST(PdbParser, ShortLinesEndingAfterTheCoordinatesAreAtomsWithDefaults) {
  std::string line = pdb_line({.name = " N  ", .x = 1, .y = 2, .z = 3});
  line = line.substr(0, 54) + "\n";
  const ParsedStructure parsed = parse_pdb(line, "t.pdb");
  EXPECT_DOUBLE_EQ(parsed.atoms[0].occupancy, 1.0);
  EXPECT_EQ(parsed.atoms[0].element, "N");
  EXPECT_DOUBLE_EQ(parsed.atoms[0].position.z, 3.0);
}

TEST(PdbParser, NumbersModelsAndStopsAtEnd) {
  const std::string text = "MODEL        1\n" + pdb_line({}) + "ENDMDL\nMODEL        2\n" + pdb_line({.x = 5}) +
                           "ENDMDL\n" + pdb_line({.x = 7}) + "END\n" + pdb_line({.x = 9});
  const ParsedStructure parsed = parse_pdb(text, "t.pdb");
  ASSERT_EQ(parsed.atoms.size(), 3u);
  EXPECT_EQ(parsed.model_count, 3);
  EXPECT_EQ(parsed.atoms[0].model_index, 0);
  EXPECT_EQ(parsed.atoms[1].model_index, 1);
  EXPECT_EQ(parsed.atoms[2].model_index, 2);  // atoms after ENDMDL without MODEL start a model
}

TEST(PdbParser, HandlesWindowsLineEndings) {
  std::string line = pdb_line({.element = "S"});
  line.insert(line.size() - 1, "\r");
  const ParsedStructure parsed = parse_pdb(line + line, "t.pdb");
  ASSERT_EQ(parsed.atoms.size(), 2u);
  EXPECT_EQ(parsed.atoms[1].element, "S");
  EXPECT_EQ(parsed.atoms[1].line, 2u);
}

TEST(PdbParser, RejectsANonNumericCoordinateNamingFileLineAndColumns) {
  std::string line = pdb_line({});
  line.replace(30, 8, "     abc");
  try {
    parse_pdb("REMARK\n" + line, "x.pdb");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "x.pdb:line 2: ATOM record has a non-numeric x coordinate 'abc' (columns 31-38)");
  }
}

// An ATOM line with `text` written over `width` columns from (0-based) `first`.
std::string with_field(std::size_t first, std::size_t width, const std::string& text) {
  std::string line = pdb_line({});
  return line.replace(first, width, text);
}

// Found by pdb_fuzzer: "nan" and "inf" parse as numbers, and were taken as coordinates.
TEST(PdbParser, RejectsNonFiniteCoordinatesAndOccupancy) {
  expect_input_error([&] { parse_pdb(with_field(38, 8, "     nan"), "x.pdb"); },
                     {"x.pdb:line 1:", "non-finite y coordinate 'nan' (columns 39-46)"});
  expect_input_error([&] { parse_pdb(with_field(46, 8, "    -inf"), "x.pdb"); }, {"x.pdb:line 1:", "non-finite z coordinate '-inf'"});
  expect_input_error([&] { parse_pdb(with_field(54, 6, "   inf"), "x.pdb"); },
                     {"x.pdb:line 1:", "non-finite occupancy 'inf' (columns 55-60)"});
}

// 1e+300 fits a coordinate field and parsed as a finite number; further on it overflowed the
// bake's bead grid (a float-to-int cast). No structure reaches a million Å.
TEST(PdbParser, RejectsFarOffCoordinates) {
  expect_input_error([&] { parse_pdb(with_field(30, 8, "  1e+300"), "x.pdb"); },
                     {"x.pdb:line 1:", "far-off (beyond ±1e6 Å) x coordinate '1e+300'"});
  expect_input_error([&] { parse_pdb(with_field(46, 8, "-1000001"), "x.pdb"); },
                     {"x.pdb:line 1:", "far-off (beyond ±1e6 Å) z coordinate"});
  EXPECT_EQ(parse_pdb(with_field(30, 8, "9999.999"), "x.pdb").atoms.at(0).position.x, 9999.999);
}

TEST(PdbParser, RejectsTruncatedRecords) {
  const std::string line = pdb_line({}).substr(0, 45) + "\n";
  expect_input_error([&] { parse_pdb(pdb_line({}) + line, "x.pdb"); }, {"x.pdb:line 2:", "truncated", "31-54"});
}

TEST(PdbParser, RejectsGarbledResidueNumberAndOccupancy) {
  std::string bad_number = pdb_line({});
  bad_number.replace(22, 4, "1x2 ");
  expect_input_error([&] { parse_pdb(bad_number, "x.pdb"); }, {"x.pdb:line 1:", "residue number '1x2'", "23-26"});
  std::string bad_occupancy = pdb_line({});
  bad_occupancy.replace(54, 6, "  1..0");
  expect_input_error([&] { parse_pdb(bad_occupancy, "x.pdb"); }, {"x.pdb:line 1:", "occupancy '1..0'", "55-60"});
}

TEST(PdbParser, RejectsTextWithoutAtoms) {
  expect_input_error([] { parse_pdb("HEADER    NOTHING\nREMARK 1\nEND\n", "x.pdb"); }, {"x.pdb:", "no ATOM or HETATM"});
  expect_input_error([] { parse_pdb("", "empty.pdb"); }, {"empty.pdb:", "no ATOM or HETATM"});
}

}  // namespace
}  // namespace nano::structure
