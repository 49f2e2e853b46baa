#include "bake/structure/structure_reader.hpp"
#include "bake/structure/structure_text.hpp"

#include <zlib.h>

#include "tests/structure/structure_test_support.hpp"

namespace nano::structure {
namespace {

using testing::expect_input_error;
using testing::pdb_line;
using testing::TempFile;

std::string gzip(const std::string& text) {
  std::string out(compressBound(text.size()) + 64, '\0');
  z_stream s{};
  deflateInit2(&s, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);  // +16: gzip wrapper
  s.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  s.avail_in = static_cast<uInt>(text.size());
  s.next_out = reinterpret_cast<Bytef*>(out.data());
  s.avail_out = static_cast<uInt>(out.size());
  deflate(&s, Z_FINISH);
  out.resize(s.total_out);
  deflateEnd(&s);
  return out;
}

const std::string kSmallPdb = pdb_line({.name = " N  ", .x = 1, .element = "N"}) + pdb_line({.name = " CA ", .x = 2}) +
                              pdb_line({.record = "HETATM", .name = " O  ", .residue = "HOH", .residue_number = 9, .element = "O"});

TEST(StructureText, ReadsPlainAndGzippedFilesAlike) {
  const TempFile plain("plain.pdb", kSmallPdb);
  const TempFile packed("packed.pdb.gz", gzip(kSmallPdb));
  const TempFile misnamed("packed_without_suffix.pdb", gzip(kSmallPdb));
  EXPECT_EQ(read_structure_text(plain.path()), kSmallPdb);
  EXPECT_EQ(read_structure_text(packed.path()), kSmallPdb);
  EXPECT_EQ(read_structure_text(misnamed.path()), kSmallPdb);  // recognised by magic bytes
}

TEST(StructureText, RejectsMissingBinaryAndCorruptFiles) {
  expect_input_error([] { read_structure_text("/nonexistent/dir/x.pdb"); }, {"/nonexistent/dir/x.pdb", "does not exist"});
  const TempFile binary("binary.pdb", std::string("ATOM  \n\x01\x02\x00\xff", 11));
  expect_input_error([&] { read_structure_text(binary.path()); }, {binary.path().string() + ":line 2:", "binary data"});
  const std::string packed = gzip(kSmallPdb);
  const TempFile truncated("truncated.pdb.gz", packed.substr(0, packed.size() / 2));
  expect_input_error([&] { read_structure_text(truncated.path()); }, {"truncated.pdb.gz", "truncated gzip"});
  std::string garbled = packed;
  for (std::size_t i = 12; i < 40 && i < garbled.size(); ++i) garbled[i] = static_cast<char>(0xAA);
  const TempFile corrupt("corrupt.pdb.gz", garbled);
  expect_input_error([&] { read_structure_text(corrupt.path()); }, {"corrupt.pdb.gz", "gzip"});
}

// What read_structure_text does once it has the bytes, from memory: the name only labels errors.
TEST(StructureText, TurnsBytesInMemoryIntoText) {
  EXPECT_EQ(structure_text_from_bytes(kSmallPdb, "plain.pdb"), kSmallPdb);
  EXPECT_EQ(structure_text_from_bytes(gzip(kSmallPdb), "any name"), kSmallPdb);
  const std::size_t half = kSmallPdb.size() / 2;
  EXPECT_EQ(structure_text_from_bytes(gzip(kSmallPdb.substr(0, half)) + gzip(kSmallPdb.substr(half)), "two members"), kSmallPdb);
  EXPECT_EQ(structure_text_from_bytes("", "empty.pdb"), "");
  expect_input_error([] { structure_text_from_bytes(std::string("ATOM\0", 5), "label.pdb"); }, {"label.pdb:line 1:", "binary data"});
  const std::string packed = gzip(kSmallPdb);
  expect_input_error([&] { structure_text_from_bytes(packed.substr(0, 20), "cut.gz"); }, {"cut.gz:", "truncated gzip"});
  expect_input_error([&] { structure_text_from_bytes(gzip(std::string("\x01\x02", 2)), "inside.gz"); }, {"inside.gz:", "binary data"});
  // Bytes after the last member that do not start another: where they are in the file (this said
  // "byte 2", counting in the member that followed).
  expect_input_error([&] { structure_text_from_bytes(packed + "trailing", "tail.gz"); },
                     {"tail.gz:byte " + std::to_string(packed.size() + 2) + ":", "corrupt gzip stream"});
}

TEST(StructureReader, DetectsTheFormatByNameThenContent) {
  EXPECT_EQ(detect_structure_format("a.cif", ""), StructureFormat::Mmcif);
  EXPECT_EQ(detect_structure_format("a.CIF.gz", ""), StructureFormat::Mmcif);
  EXPECT_EQ(detect_structure_format("a.mmcif", ""), StructureFormat::Mmcif);
  EXPECT_EQ(detect_structure_format("a.ent.gz", "data_x"), StructureFormat::Pdb);
  EXPECT_EQ(detect_structure_format("a.txt", "# made by hand\n\ndata_x\n"), StructureFormat::Mmcif);
  EXPECT_EQ(detect_structure_format("a", "ATOM      1"), StructureFormat::Pdb);
}

TEST(StructureReader, AppliesThePolicyAndAssignsRadii) {
  const TempFile file("policy.pdb.gz", gzip(kSmallPdb));
  const Molecule m = read_molecule(file.path(), {});
  EXPECT_EQ(m.source, file.path().string());
  EXPECT_EQ(m.format, StructureFormat::Pdb);
  EXPECT_EQ(m.model_count, 1);
  ASSERT_EQ(m.atoms.size(), 2u);  // water gone
  EXPECT_DOUBLE_EQ(m.atoms[0].radius, 1.55);
  EXPECT_DOUBLE_EQ(m.atoms[1].radius, 1.70);
  EXPECT_TRUE(m.warnings.empty());
  EXPECT_EQ(read_molecule(file.path(), {.keep_water = true}).atoms.size(), 3u);
}

TEST(StructureReader, WarnsAboutUnknownElementsAndUsesTheFallbackRadius) {
  const std::string text = kSmallPdb + pdb_line({.record = "HETATM", .name = "XE  ", .residue = " XE", .residue_number = 5, .element = "XE"}) +
                           pdb_line({.record = "HETATM", .name = "XE  ", .residue = " XE", .residue_number = 6, .element = "XE"});
  const Molecule m = molecule_from_text(text, StructureFormat::Pdb, "xe.pdb", {});
  ASSERT_EQ(m.atoms.size(), 4u);
  EXPECT_DOUBLE_EQ(m.atoms[3].radius, 1.7);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("'Xe'"), std::string::npos) << m.warnings[0];
  EXPECT_NE(m.warnings[0].find("2 atom(s)"), std::string::npos) << m.warnings[0];
}

TEST(StructureReader, WarnsAboutDuplicatesThatAreNotAlternateLocations) {
  const Molecule m = molecule_from_text(kSmallPdb + kSmallPdb, StructureFormat::Pdb, "dup.pdb", {});
  EXPECT_EQ(m.atoms.size(), 2u);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("2 atom record(s)"), std::string::npos) << m.warnings[0];
}

TEST(StructureReader, RejectsAFileWhoseAtomsAreAllRemoved) {
  const std::string water = pdb_line({.record = "HETATM", .name = " O  ", .residue = "HOH", .element = "O"});
  expect_input_error([&] { molecule_from_text(water, StructureFormat::Pdb, "w.pdb", {}); }, {"w.pdb:", "removed all 1 atom"});
}

TEST(StructureReader, ReadsMmcifThroughTheSameEntryPoint) {
  const TempFile file("one.cif", "data_1\n_atom_site.label_atom_id FE\n_atom_site.label_comp_id FE\n"
                                 "_atom_site.Cartn_x 1\n_atom_site.Cartn_y 2\n_atom_site.Cartn_z 3\n");
  const Molecule m = read_molecule(file.path(), {});
  EXPECT_EQ(m.format, StructureFormat::Mmcif);
  ASSERT_EQ(m.atoms.size(), 1u);
  EXPECT_EQ(m.atoms[0].element, "Fe");
  EXPECT_DOUBLE_EQ(m.atoms[0].radius, 2.05);
}

}  // namespace
}  // namespace nano::structure
