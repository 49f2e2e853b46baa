// `nanoview export` end to end: CSV rows, PDB and mmCIF read back by gemmi, all compared with the
// plane-geometry oracle of hand_scene.hpp; refusals leave nothing behind.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "format/writer.hpp"
#include "tests/oracle/hand_scene.hpp"

namespace nano::explicit_test {
namespace {

namespace fs = std::filesystem;

struct CliResult {
  int code;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class ExportCli : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::path(NANO_TEST_WORK_DIR) / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }

  fs::path write(const SampleScene& s, const std::string& name = "scene.nup") {
    const fs::path p = dir_ / name;
    format::write_package(p, format::test::sections_of(s, format::Compression::zstd_if_smaller));
    return p;
  }

  CliResult run(const std::string& args) {
    const std::string cmd = std::string(NANOVIEW) + " " + args + " >" + (dir_ / "stdout").string() + " 2>" + (dir_ / "stderr").string();
    const int status = std::system(cmd.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir_ / "stdout"), slurp(dir_ / "stderr")};
  }

  CliResult export_box(const fs::path& pkg, const std::string& box, const fs::path& out) {
    return run("export " + pkg.string() + " --box=" + box + " -o " + out.string());
  }

  // "count" then one "x y z resname" line per atom of the first model, as gemmi reads the file.
  std::vector<std::string> gemmi_lines(const fs::path& file) {
    const std::string script =
        "import gemmi, sys\n"
        "st = gemmi.read_structure(sys.argv[1])\n"
        "atoms = [(a, r) for ch in st[0] for r in ch for a in r]\n"
        "print(len(atoms))\n"
        "for a, r in atoms: print('%.4f %.4f %.4f %s' % (a.pos.x, a.pos.y, a.pos.z, r.name))\n";
    std::ofstream(dir_ / "read.py") << script;
    const std::string cmd = std::string(NANO_PYTHON) + " " + (dir_ / "read.py").string() + " " + file.string() + " >" +
                            (dir_ / "gemmi.txt").string() + " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << slurp(dir_ / "gemmi.txt");
    std::vector<std::string> lines;
    std::istringstream in(slurp(dir_ / "gemmi.txt"));
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }

  fs::path dir_;
};

const std::string kAll = "-5000,-5000,-5000,5000,5000,5000";

// Positions of `expected` matched one to one with `found` (per-axis tolerance; atoms of the hand
// scene are far further apart than it, so the match is unambiguous).
void expect_same_positions(const Expected& expected, const std::vector<glm::dvec3>& found, double tol) {
  ASSERT_EQ(found.size(), expected.size());
  std::vector<glm::dvec3> left;
  for (const auto& [key, atom] : expected) left.push_back(atom.position);
  for (const glm::dvec3& p : found) {
    const auto match = std::find_if(left.begin(), left.end(), [&](const glm::dvec3& q) {
      return std::abs(q.x - p.x) <= tol && std::abs(q.y - p.y) <= tol && std::abs(q.z - p.z) <= tol;
    });
    ASSERT_NE(match, left.end()) << "unexpected or repeated atom at " << p.x << " " << p.y << " " << p.z;
    left.erase(match);
  }
}

TEST_F(ExportCli, CsvHeaderAndRowsMatchPlaneGeometry) {
  const SampleScene s = hand_scene();
  const fs::path pkg = write(s);
  for (const auto& [box, lo, hi] : {std::tuple{kAll, glm::dvec3(-5000), glm::dvec3(5000)},
                                    std::tuple{std::string("0,0,-10,64,70,10"), glm::dvec3(0, 0, -10), glm::dvec3(64, 70, 10)}}) {
    SCOPED_TRACE(box);
    const CliResult r = export_box(pkg, box, dir_ / "atoms.csv");
    ASSERT_EQ(r.code, 0) << r.err;
    Expected expected;
    std::set<std::tuple<std::uint32_t, int, int, int, int, std::uint32_t>> copies;
    for (const auto& [key, atom] : expected_atoms(s)) {
      const glm::dvec3& p = atom.position;
      if (glm::all(glm::greaterThanEqual(p, lo)) && glm::all(glm::lessThanEqual(p, hi))) {
        expected.emplace(key, atom);
        copies.insert({key.compartment_instance, key.kind, key.cell.x, key.cell.y, key.cell.z, key.instance});
      }
    }
    EXPECT_EQ(r.out, (dir_ / "atoms.csv").string() + ": " + std::to_string(copies.size()) + " copies, " +
                         std::to_string(expected.size()) + " atoms\n");
    std::istringstream in(slurp(dir_ / "atoms.csv"));
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "copy,type,chain,residue,atom,element,x,y,z,radius,kind");
    std::vector<glm::dvec3> found;
    std::set<std::string> copy_numbers;
    while (std::getline(in, line)) {
      std::vector<std::string> f;
      std::istringstream fields(line);
      for (std::string v; std::getline(fields, v, ',');) f.push_back(v);
      ASSERT_EQ(f.size(), 11u) << line;
      EXPECT_TRUE(f[10] == "membrane" || f[10] == "core") << line;  // the hand scene has no medium
      copy_numbers.insert(f[0]);
      EXPECT_TRUE((f[1] == "0" && f[2] == "A" && f[3] == "LYS") || (f[1] == "1" && f[3] == "HEM" && f[4] == "FE" && f[5] == "FE")) << line;
      found.emplace_back(std::stod(f[6]), std::stod(f[7]), std::stod(f[8]));
    }
    EXPECT_EQ(copy_numbers.size(), copies.size());
    expect_same_positions(expected, found, 1e-3);
  }
}

TEST_F(ExportCli, PdbAndMmcifReadBackByGemmi) {
  const SampleScene s = hand_scene();
  const fs::path pkg = write(s);
  const Expected expected = expected_atoms(s);
  for (const char* name : {"atoms.pdb", "atoms.cif"}) {
    SCOPED_TRACE(name);
    const CliResult r = export_box(pkg, kAll, dir_ / name);
    ASSERT_EQ(r.code, 0) << r.err;
    const std::vector<std::string> lines = gemmi_lines(dir_ / name);
    ASSERT_FALSE(lines.empty());
    EXPECT_EQ(std::stoul(lines[0]), expected.size());
    std::vector<glm::dvec3> found;
    std::set<std::string> residues;
    for (std::size_t i = 1; i < lines.size(); ++i) {
      std::istringstream l(lines[i]);
      glm::dvec3 p;
      std::string residue;
      l >> p.x >> p.y >> p.z >> residue;
      found.push_back(p);
      residues.insert(residue);
    }
    EXPECT_EQ(residues, (std::set<std::string>{"LYS", "HEM"}));
    // PDB keeps 3 decimals: half a unit of the last place per axis.
    expect_same_positions(expected, found, 6e-4);
  }
}

TEST_F(ExportCli, InvalidPackageRefusedWithTheValidatorsMessage) {
  SampleScene s = hand_scene();
  s.compartment_instances[1].compartment = 99;
  const fs::path pkg = write(s);
  const CliResult r = export_box(pkg, kAll, dir_ / "atoms.csv");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("index-out-of-range: compartment_instances[1]: compartment 99"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "atoms.csv"));
}

TEST_F(ExportCli, UnwritableOutputLeavesNothing) {
  const fs::path pkg = write(hand_scene());
  const CliResult r = export_box(pkg, kAll, dir_ / "missing" / "atoms.csv");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("cannot create temporary file"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "missing"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 3);  // scene.nup, stdout, stderr
}

TEST_F(ExportCli, BadArgumentsRefused) {
  const fs::path pkg = write(hand_scene());
  for (const std::string& box : {std::string("1,2,3"), std::string("0,0,0,1,1,x"), std::string("5,0,0,1,1,1")}) {
    const CliResult r = export_box(pkg, box, dir_ / "atoms.csv");
    EXPECT_EQ(r.code, 1) << box;
    EXPECT_NE(r.err.find("--box"), std::string::npos) << r.err;
  }
  EXPECT_EQ(export_box(pkg, kAll, dir_ / "atoms.xyz").code, 1);
  EXPECT_FALSE(fs::exists(dir_ / "atoms.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "atoms.xyz"));
}

// PDB cannot hold coordinates beyond 9999.999: refused, and an existing file stays as it was.
TEST_F(ExportCli, PdbCoordinateOverflowRefusedAndExistingFileKept) {
  std::vector<Placement> far = {{0, {0, 0, 1}, 0, {20000, 0, 0}}};
  const fs::path pkg = write(hand_scene(far));
  std::ofstream(dir_ / "atoms.pdb") << "old\n";
  const CliResult r = export_box(pkg, "0,-100,-100,30000,300,100", dir_ / "atoms.pdb");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("write .cif instead"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir_ / "atoms.pdb"), "old\n");
  const CliResult cif = export_box(pkg, "0,-100,-100,30000,300,100", dir_ / "atoms.cif");
  ASSERT_EQ(cif.code, 0) << cif.err;
  EXPECT_EQ(std::stoul(gemmi_lines(dir_ / "atoms.cif")[0]), expected_atoms(hand_scene(far), far).size());
}

// 60 × 60 × 10 INSIDE boxes alternating two cubes of two copies (4 and 6 atoms): 180,000 atoms.
TEST_F(ExportCli, MoreThanPdbAtomsRefusedButMmcifWritesThemAll) {
  const std::vector<Placement> core = {{2, {0, 0, 1}, 0, {0, 0, 0}}};
  SampleScene s = hand_scene(core);
  s.compartments[2].grid_dims = glm::uvec4(60, 60, 10, 0);
  s.compartments[2].core_masks = glm::uvec4(0);
  s.occupancy.assign(36000, gpu::NANO_BOX_INSIDE);
  s.boundary_boxes.clear();
  s.mask_words.clear();
  const fs::path pkg = write(s);
  const CliResult r = export_box(pkg, kAll, dir_ / "atoms.pdb");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("at most 99,999 atoms"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "atoms.pdb"));
  const CliResult cif = export_box(pkg, kAll, dir_ / "atoms.cif");
  ASSERT_EQ(cif.code, 0) << cif.err;
  EXPECT_NE(cif.out.find("72000 copies, 180000 atoms"), std::string::npos) << cif.out;
  EXPECT_EQ(gemmi_lines(dir_ / "atoms.cif")[0], "180000");
}

}  // namespace
}  // namespace nano::explicit_test
