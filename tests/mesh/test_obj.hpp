#pragma once
// Hand-built OBJ meshes for the tests: an octahedron with an octahedral UV map, whose every
// property is known by construction, plus helpers to write planted-defect variants to disk and to
// expect the reader's refusal of them.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "bake/mesh/mesh_reader.hpp"
#include "common/error.hpp"

namespace nano::mesh::testing {

// Vertices 1..6: +X, +Y, −X, −Y, +Z, −Z. UVs: the octahedral map (x, y) for the upper half,
// (sign x·(1−|y|), sign y·(1−|x|)) for the lower half, moved to [0,1]². Faces 0..3 are the upper
// faces, 4..7 the lower ones; all wind counter-clockwise seen from outside and in UV. One UV
// chart; the 4 edges to −Z are seams.
inline const std::string octahedron_vertices =
    "v 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n";
inline const std::string octahedron_uvs =
    "vt 1 0.5\nvt 0.5 1\nvt 0 0.5\nvt 0.5 0\nvt 0.5 0.5\nvt 1 1\nvt 0 1\nvt 0 0\nvt 1 0\n";
inline const std::string octahedron_faces =
    "f 1/1 2/2 5/5\nf 2/2 3/3 5/5\nf 3/3 4/4 5/5\nf 4/4 1/1 5/5\n"
    "f 2/2 1/1 6/6\nf 3/3 2/2 6/7\nf 4/4 3/3 6/8\nf 1/1 4/4 6/9\n";
inline const std::string octahedron = octahedron_vertices + octahedron_uvs + octahedron_faces;

// A scratch directory per test, removed afterwards.
class TempDir {
public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("nano_mesh_" + std::string(info->test_suite_name()) + "_" + info->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const auto file = path_ / name;
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }
  const std::filesystem::path& path() const { return path_; }

private:
  std::filesystem::path path_;
};

// read_proxy_mesh(file) throws an InputError naming the file, at `where`, whose rule contains `rule_part`.
inline void expect_input_error(const std::filesystem::path& file, const std::string& where, const std::string& rule_part) {
  try {
    read_proxy_mesh(file);
    ADD_FAILURE() << "no InputError for " << file;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file.string());
    EXPECT_NE(std::string(e.what()).find(file.filename().string()), std::string::npos) << e.what();
    EXPECT_EQ(e.where(), where) << e.what();
    EXPECT_NE(e.rule().find(rule_part), std::string::npos) << e.what();
  }
}

}  // namespace nano::mesh::testing
