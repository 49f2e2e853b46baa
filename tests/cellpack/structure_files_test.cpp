// Finding an ingredient's structure in a folder: by id or file name, any case, any of the
// extensions, gzipped or not; a miss lists what was tried.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "bake/cellpack/structure_files.hpp"

namespace nano::cellpack {
namespace {

namespace fs = std::filesystem;

TEST(StructureFiles, NamesTriedForAnIdAFileAndADatabasePath) {
  EXPECT_EQ(structure_file_names("1AO6"),
            (std::vector<std::string>{"1AO6", "1AO6.pdb", "1AO6.pdb.gz", "1AO6.cif", "1AO6.cif.gz", "1AO6.mmcif", "1AO6.mmcif.gz",
                                      "1AO6.ent", "1AO6.ent.gz", "pdb1AO6.ent", "pdb1AO6.ent.gz"}));
  const std::vector<std::string> file = structure_file_names("autoPACKserver/other/HIV1_ENV_4ncoABEFIJ.pdb");
  ASSERT_GE(file.size(), 3u);
  EXPECT_EQ(file[0], "HIV1_ENV_4ncoABEFIJ.pdb");  // as written first
  EXPECT_EQ(file[1], "HIV1_ENV_4ncoABEFIJ.pdb.gz");
  EXPECT_EQ(file[2], "HIV1_ENV_4ncoABEFIJ.cif");
  EXPECT_EQ(structure_file_names("github:x/7hvp.cif.gz")[1], "7hvp.pdb");
  EXPECT_EQ(structure_file_names(".pdb"), std::vector<std::string>{".pdb"});
}

TEST(StructureFiles, FoundCaseInsensitivelyWithAnyExtensionAndMissesListed) {
  const fs::path dir = fs::temp_directory_path() / "nano_structure_files";
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* name : {"1ao6.cif.gz", "Pdb7HVP.ent", "HIV1_ENV_4ncoABEFIJ.PDB", "b.pdb", "B.pdb"}) std::ofstream(dir / name) << "x";
  const StructureFolder folder(dir);
  EXPECT_EQ(folder.find("1AO6").found, dir / "1ao6.cif.gz");
  EXPECT_EQ(folder.find("7hvp").found, dir / "Pdb7HVP.ent");
  EXPECT_EQ(folder.find("autoPACKserver/other/HIV1_ENV_4ncoABEFIJ.pdb").found, dir / "HIV1_ENV_4ncoABEFIJ.PDB");
  EXPECT_EQ(folder.find("b").found, dir / "B.pdb");  // of two names differing in case, the first by name
  const StructureFolder::Lookup miss = folder.find("1hzh");
  EXPECT_FALSE(miss.found);
  EXPECT_EQ(miss.tried.size(), 11u);
  EXPECT_FALSE(StructureFolder(dir / "absent").find("1ao6").found);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace nano::cellpack
