#include "bake/structure/cif_tokenizer.hpp"
#include "bake/structure/mmcif_parser.hpp"

#include <vector>

#include "tests/structure/structure_test_support.hpp"

namespace nano::structure {
namespace {

using testing::expect_input_error;

std::vector<CifToken> all_tokens(std::string_view text) {
  CifTokenizer tokenizer(text, "t.cif");
  std::vector<CifToken> tokens;
  for (CifToken t = tokenizer.next(); t.kind != CifTokenKind::End; t = tokenizer.next()) tokens.push_back(t);
  return tokens;
}

TEST(CifTokenizer, SplitsQuotesTextFieldsNullsAndComments) {
  const std::string text =
      "# comment\ndata_X\n_a.b 'O5'' \"a b\" '.' . ? # trailing comment\n;line one\nline two\n;\nloop_ _c.d x\n";
  const auto t = all_tokens(text);
  ASSERT_EQ(t.size(), 11u);
  EXPECT_EQ(t[0].kind, CifTokenKind::DataBlock);
  EXPECT_EQ(t[0].text, "X");
  EXPECT_EQ(t[0].line, 2u);
  EXPECT_EQ(t[1].kind, CifTokenKind::Tag);
  EXPECT_EQ(t[2].text, "O5'");  // a quote closes only before whitespace
  EXPECT_EQ(t[3].text, "a b");
  EXPECT_EQ(t[4].kind, CifTokenKind::Value);  // quoted '.' is a literal dot
  EXPECT_EQ(t[4].text, ".");
  EXPECT_EQ(t[5].kind, CifTokenKind::Inapplicable);
  EXPECT_EQ(t[6].kind, CifTokenKind::Unknown);
  EXPECT_EQ(t[7].kind, CifTokenKind::Value);
  EXPECT_EQ(t[7].text, "line one\nline two");
  EXPECT_EQ(t[7].line, 4u);
  EXPECT_EQ(t[8].kind, CifTokenKind::Loop);
  EXPECT_EQ(t[8].line, 7u);
  EXPECT_EQ(t[10].text, "x");
}

TEST(CifTokenizer, RejectsUnterminatedQuotesAndTextFields) {
  expect_input_error([] { all_tokens("data_X\n_a.b 'open\n"); }, {"t.cif:line 2:", "unterminated single-quoted"});
  expect_input_error([] { all_tokens("data_X\n_a.b \"open'\n"); }, {"t.cif:line 2:", "unterminated double-quoted"});
  expect_input_error([] { all_tokens("data_X\n_a.b\n;never closed\nmore\n"); }, {"t.cif:line 3:", "unterminated ';' text field"});
  expect_input_error([] { all_tokens("data_X\nstop_\n"); }, {"t.cif:line 2:", "reserved"});
}

const char* const kHeader =
    "loop_\n_atom_site.group_PDB\n_atom_site.Cartn_z\n_atom_site.label_atom_id\n_atom_site.auth_atom_id\n"
    "_atom_site.label_comp_id\n_atom_site.label_asym_id\n_atom_site.auth_asym_id\n_atom_site.label_seq_id\n"
    "_atom_site.auth_seq_id\n_atom_site.pdbx_PDB_ins_code\n_atom_site.label_alt_id\n_atom_site.Cartn_x\n"
    "_atom_site.Cartn_y\n_atom_site.occupancy\n_atom_site.type_symbol\n_atom_site.pdbx_PDB_model_num\n";

TEST(MmcifParser, ReadsAtomSiteInAnyColumnOrderPreferringAuthorIds) {
  const std::string text = std::string("data_T\n_entry.id T\n#\n") + kHeader +
                           "ATOM   3.5 CA CA ALA A B 1 10 ? . 1.25 -2 0.75 C 1\n"
                           "HETATM 0.0 FE FE HEM C C . 200 A A 4 5 1 FE 1\n"
                           "ATOM   9 CA CA ALA A B 1 10 ? . 1 1 1 C 2\n"
                           "#\nloop_\n_other.x\n_other.y\n1 2\n";
  const ParsedStructure parsed = parse_mmcif(text, "t.cif");
  ASSERT_EQ(parsed.atoms.size(), 3u);
  EXPECT_EQ(parsed.model_count, 2);
  const Atom& a = parsed.atoms[0];
  EXPECT_EQ(a.position, glm::dvec3(1.25, -2.0, 3.5));
  EXPECT_EQ(a.atom_name, "CA");
  EXPECT_EQ(a.residue_name, "ALA");
  EXPECT_EQ(a.chain, "B");  // auth_asym_id, not label_asym_id
  EXPECT_EQ(a.residue_number, 10);
  EXPECT_EQ(a.insertion_code, "");
  EXPECT_EQ(a.alt_loc, ' ');
  EXPECT_DOUBLE_EQ(a.occupancy, 0.75);
  EXPECT_EQ(a.element, "C");
  EXPECT_FALSE(a.hetatm);
  EXPECT_EQ(a.line, 21u);
  const Atom& fe = parsed.atoms[1];
  EXPECT_TRUE(fe.hetatm);
  EXPECT_EQ(fe.element, "Fe");
  EXPECT_EQ(fe.residue_number, 200);
  EXPECT_EQ(fe.insertion_code, "A");
  EXPECT_EQ(fe.alt_loc, 'A');
  EXPECT_EQ(parsed.atoms[2].model_index, 1);
}

TEST(MmcifParser, FallsBackToLabelIdsAndInfersElements) {
  const std::string text =
      "data_L\nloop_\n_atom_site.label_atom_id\n_atom_site.label_comp_id\n_atom_site.label_asym_id\n"
      "_atom_site.label_seq_id\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n_atom_site.Cartn_z\n"
      "\"O5'\" DA X 3 1 2 3\nCA CA Y . 4(2) 5 6\n";
  const ParsedStructure parsed = parse_mmcif(text, "t.cif");
  ASSERT_EQ(parsed.atoms.size(), 2u);
  EXPECT_EQ(parsed.atoms[0].atom_name, "O5'");
  EXPECT_EQ(parsed.atoms[0].element, "O");
  EXPECT_EQ(parsed.atoms[0].chain, "X");
  EXPECT_EQ(parsed.atoms[0].residue_number, 3);
  EXPECT_EQ(parsed.atoms[1].element, "Ca");
  EXPECT_EQ(parsed.atoms[1].residue_number, kNoResidueNumber);
  EXPECT_DOUBLE_EQ(parsed.atoms[1].position.x, 4.0);  // "(2)" is a standard uncertainty
  EXPECT_DOUBLE_EQ(parsed.atoms[1].occupancy, 1.0);
  EXPECT_EQ(parsed.model_count, 1);
}

TEST(MmcifParser, UsesOnlyTheFirstDataBlock) {
  const std::string text = "data_A\n_atom_site.label_atom_id N\n_atom_site.Cartn_x 1\n_atom_site.Cartn_y 2\n"
                           "_atom_site.Cartn_z 3\n_atom_site.type_symbol N\n"
                           "data_B\nloop_\n_atom_site.label_atom_id\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n"
                           "_atom_site.Cartn_z\nC 0 0 0\nO 0 0 0\n";
  const ParsedStructure parsed = parse_mmcif(text, "t.cif");  // also: tag-value pairs, no loop
  ASSERT_EQ(parsed.atoms.size(), 1u);
  EXPECT_EQ(parsed.atoms[0].element, "N");
  EXPECT_EQ(parsed.atoms[0].position, glm::dvec3(1, 2, 3));
}

TEST(MmcifParser, RejectsMissingCoordinateColumns) {
  const std::string text = "data_A\nloop_\n_atom_site.label_atom_id\n_atom_site.Cartn_y\n_atom_site.Cartn_z\nC 0 0\n";
  expect_input_error([&] { parse_mmcif(text, "m.cif"); }, {"m.cif:line 2:", "no Cartn_x column"});
  const std::string no_name = "data_A\nloop_\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n_atom_site.Cartn_z\n0 0 0\n";
  expect_input_error([&] { parse_mmcif(no_name, "m.cif"); }, {"m.cif:line 2:", "atom_id"});
}

TEST(MmcifParser, RejectsLoopsWhoseValueCountIsNotAMultipleOfTheColumns) {
  const std::string text = "data_A\nloop_\n_atom_site.label_atom_id\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n"
                           "_atom_site.Cartn_z\nC 0 0 0\nO 1 1\n";
  expect_input_error([&] { parse_mmcif(text, "m.cif"); }, {"m.cif:line 2:", "7 values", "multiple of its 4 columns"});
  const std::string other = "data_A\nloop_\n_x.a\n_x.b\n1 2 3\n";
  expect_input_error([&] { parse_mmcif(other, "m.cif"); }, {"m.cif:line 2:", "3 values"});
}

TEST(MmcifParser, RejectsNonNumericValues) {
  const std::string text = "data_A\nloop_\n_atom_site.label_atom_id\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n"
                           "_atom_site.Cartn_z\nC 0 0 0\nO 1 abc 1\n";
  expect_input_error([&] { parse_mmcif(text, "m.cif"); }, {"m.cif:line 8:", "Cartn_y", "'abc'"});
  const std::string unknown_coordinate = "data_A\n_atom_site.label_atom_id C\n_atom_site.Cartn_x ?\n"
                                         "_atom_site.Cartn_y 0\n_atom_site.Cartn_z 0\n";
  expect_input_error([&] { parse_mmcif(unknown_coordinate, "m.cif"); }, {"m.cif:line 3:", "Cartn_x", "'?'"});
}

// Found by mmcif_fuzzer: "nan" and "inf" parse as numbers, and were taken as coordinates.
TEST(MmcifParser, RejectsNonFiniteValues) {
  const std::string header = "data_A\nloop_\n_atom_site.label_atom_id\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n"
                             "_atom_site.Cartn_z\n_atom_site.occupancy\n";
  expect_input_error([&] { parse_mmcif(header + "C 0 0 0 1\nO nan 1 1 1\n", "m.cif"); },
                     {"m.cif:line 9:", "Cartn_x has a non-finite value 'nan'"});
  expect_input_error([&] { parse_mmcif(header + "C 0 0 -inf(2) 1\n", "m.cif"); },
                     {"m.cif:line 8:", "Cartn_z has a non-finite value '-inf(2)'"});
  expect_input_error([&] { parse_mmcif(header + "C 0 0 0 INF\n", "m.cif"); }, {"m.cif:line 8:", "occupancy has a non-finite value"});
}

TEST(MmcifParser, RejectsFarOffCoordinates) {
  const std::string header = "data_A\nloop_\n_atom_site.label_atom_id\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n"
                             "_atom_site.Cartn_z\n";
  expect_input_error([&] { parse_mmcif(header + "C 0 1e300 0\n", "m.cif"); },
                     {"m.cif:line 7:", "Cartn_y has a far-off value '1e300' (beyond ±1e6 Å)"});
  EXPECT_NO_THROW(parse_mmcif(header + "C 0 -99999.5 0\n", "m.cif"));
}

// Found by mmcif_fuzzer: an _atom_site loop holding a tag of another category shorter than
// "_atom_site." threw std::out_of_range (and a longer one ending like an item, _zzzzzzzzzzCartn_z,
// was taken for it). Such items are not _atom_site's, and are read past.
TEST(MmcifParser, ReadsPastItemsOfOtherCategoriesInTheAtomSiteLoop) {
  const std::string text = "data_A\nloop_\n_atom_site.label_atom_id\n_\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n"
                           "_x.cartn_z\n_zzzzzzzzzzCartn_z\n_atom_site.Cartn_z\nC 9 1 2 8 7 3\n";
  const ParsedStructure parsed = parse_mmcif(text, "m.cif");
  ASSERT_EQ(parsed.atoms.size(), 1u);
  EXPECT_EQ(parsed.atoms[0].position, glm::dvec3(1, 2, 3));
}

TEST(MmcifParser, RejectsFilesWithoutAtoms) {
  expect_input_error([] { parse_mmcif("data_E\n_entry.id E\n", "e.cif"); }, {"e.cif:data_E:", "no _atom_site"});
  expect_input_error([] { parse_mmcif("", "e.cif"); }, {"e.cif:", "no data_ block"});
  expect_input_error([] { parse_mmcif("_entry.id E\n", "e.cif"); }, {"e.cif:line 1:", "before the first data_"});
  const std::string empty_loop = "data_A\nloop_\n_atom_site.label_atom_id\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n"
                                 "_atom_site.Cartn_z\n#\n";
  expect_input_error([&] { parse_mmcif(empty_loop, "e.cif"); }, {"e.cif:data_A:", "no rows"});
}

TEST(MmcifParser, RejectsATagWithoutValueAndAStrayValue) {
  expect_input_error([] { parse_mmcif("data_A\n_entry.id\n_x.y 1\n", "e.cif"); }, {"e.cif:line 2:", "_entry.id has no value"});
  expect_input_error([] { parse_mmcif("data_A\nstray\n", "e.cif"); }, {"e.cif:line 2:", "'stray' has no tag"});
}

}  // namespace
}  // namespace nano::structure
