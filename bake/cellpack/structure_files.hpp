#pragma once
// Where an ingredient's structure is on disk: cellPACK recipes name it by PDB id ("1AO6"), by file
// name ("HIV1_ENV_4ncoABEFIJ.pdb") or by a path of cellPACK's database; users keep a folder of
// structures under whatever case and extension their download gave them. A structure is found in
// that folder by id or file name, case-insensitively, as .pdb, .cif, .mmcif, .ent or the PDB
// archive's pdbXXXX.ent, gzipped or not; a miss names every file name tried.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace nano::cellpack {

class StructureFolder {
public:
  // Lists `folder` once (not recursively); a folder that does not exist lists nothing.
  explicit StructureFolder(const std::filesystem::path& folder);

  struct Lookup {
    std::optional<std::filesystem::path> found;
    std::vector<std::string> tried;  // the file names looked for, in order
  };
  Lookup find(const std::string& written) const;

  const std::filesystem::path& folder() const { return folder_; }

private:
  std::filesystem::path folder_;
  std::map<std::string, std::filesystem::path> by_lower_name_;
};

// The file names a structure written as `written` may have, in the order they are tried.
std::vector<std::string> structure_file_names(const std::string& written);

}  // namespace nano::cellpack
