#pragma once
// Helpers for the structure tests: fixed-column PDB lines and self-deleting temporary files.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include <gtest/gtest.h>

#include "common/error.hpp"

namespace nano::structure::testing {

struct PdbAtomLine {
  const char* record = "ATOM";
  const char* name = " CA ";  // the 4-column field 13-16, exactly as written in the file
  char alt_loc = ' ';
  const char* residue = "ALA";
  char chain = 'A';
  int residue_number = 1;
  char insertion_code = ' ';
  double x = 0, y = 0, z = 0;
  double occupancy = 1.0;
  const char* element = "C";
};

inline std::string pdb_line(const PdbAtomLine& a) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "%-6s%5d %4s%c%3s %c%4d%c   %8.3f%8.3f%8.3f%6.2f%6.2f          %2s\n",
                a.record, 1, a.name, a.alt_loc, a.residue, a.chain, a.residue_number, a.insertion_code, a.x, a.y, a.z,
                a.occupancy, 20.0, a.element);
  return buffer;
}

// A file in the test's temporary directory, removed when the object dies.
class TempFile {
public:
  TempFile(const std::string& name, const std::string& bytes)
      : path_(std::filesystem::temp_directory_path() / ("nano_structure_test_" + std::to_string(::getpid()) + "_" + name)) {
    std::ofstream(path_, std::ios::binary) << bytes;
  }
  ~TempFile() { std::filesystem::remove(path_); }
  const std::filesystem::path& path() const { return path_; }

private:
  std::filesystem::path path_;
};

// Runs `body`, expects an InputError whose message contains every fragment in `fragments`.
template <typename Body>
void expect_input_error(Body&& body, std::initializer_list<std::string> fragments) {
  try {
    body();
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    for (const std::string& fragment : fragments)
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << "message: " << e.what() << "\nmissing: " << fragment;
  }
}

}  // namespace nano::structure::testing
