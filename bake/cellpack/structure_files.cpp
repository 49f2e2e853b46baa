#include "bake/cellpack/structure_files.hpp"

#include <algorithm>
#include <array>
#include <cctype>

namespace nano::cellpack {
namespace fs = std::filesystem;

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

constexpr std::array<const char*, 4> kExtensions = {".pdb", ".cif", ".mmcif", ".ent"};

}  // namespace

std::vector<std::string> structure_file_names(const std::string& written) {
  // Only the last path component counts: database paths and URLs name a file somewhere else.
  std::string name = written.substr(written.find_last_of("/\\:") == std::string::npos ? 0 : written.find_last_of("/\\:") + 1);
  std::vector<std::string> names;
  const auto add = [&](const std::string& n) {
    if (!n.empty() && std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
  };
  add(name);
  std::string stem = name;
  if (ends_with(lower(stem), ".gz")) stem.resize(stem.size() - 3);
  for (const char* ext : kExtensions)
    if (ends_with(lower(stem), ext)) {
      stem.resize(stem.size() - std::string(ext).size());
      break;
    }
  if (stem.empty()) return names;
  for (const char* ext : kExtensions) {
    add(stem + ext);
    add(stem + ext + ".gz");
  }
  if (stem.size() == 4) {  // a PDB id: the archive's own file name too
    add("pdb" + stem + ".ent");
    add("pdb" + stem + ".ent.gz");
  }
  return names;
}

StructureFolder::StructureFolder(const fs::path& folder) : folder_(folder) {
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code file_ec;
    if (!it->is_regular_file(file_ec)) continue;
    // Two files that differ only in case: the first by name, whatever order the folder lists them in.
    const auto [at, added] = by_lower_name_.emplace(lower(it->path().filename().string()), it->path());
    if (!added && it->path() < at->second) at->second = it->path();
  }
}

StructureFolder::Lookup StructureFolder::find(const std::string& written) const {
  Lookup out;
  out.tried = structure_file_names(written);
  for (const std::string& name : out.tried) {
    const auto it = by_lower_name_.find(lower(name));
    if (it != by_lower_name_.end()) {
      out.found = it->second;
      break;
    }
  }
  return out;
}

}  // namespace nano::cellpack
