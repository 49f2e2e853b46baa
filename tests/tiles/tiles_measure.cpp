// Generation time and achieved densities of realistic sets built from the real PDB files:
//   tiles_measure /work/shared/data/pdb
// (not a test; prints one line per set).
#include "bake/tiles/wang_sets.hpp"
#include "common/error.hpp"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>

using namespace nano::tiles;

// Tiny ATOM/HETATM reader: heavy atoms of the first model, radius 1.7 Å, centred on the centroid.
static MoleculeType read_pdb(const std::string& path, const std::string& name) {
  MoleculeType m{name, {}, 0.f, {0, 0, 1}};
  std::ifstream in(path);
  std::string line;
  glm::dvec3 sum(0.0);
  while (std::getline(in, line)) {
    if (line.rfind("ENDMDL", 0) == 0) break;
    if (line.rfind("ATOM", 0) != 0 && line.rfind("HETATM", 0) != 0) continue;
    if (line.size() < 54) continue;
    const std::string element = line.size() >= 78 ? line.substr(76, 2) : "";
    if (element.find('H') != std::string::npos && element.find("HG") == std::string::npos) continue;
    if (line.substr(17, 3) == "HOH") continue;
    const glm::vec3 c(std::stof(line.substr(30, 8)), std::stof(line.substr(38, 8)), std::stof(line.substr(46, 8)));
    m.atoms.push_back({c, 1.7f});
    sum += glm::dvec3(c);
  }
  const glm::vec3 centre(sum / double(m.atoms.size()));
  for (AtomSphere& a : m.atoms) a.centre -= centre;
  // Up axis = direction of largest spread (power iteration on the covariance), as a reader would give.
  glm::mat3 cov(0.f);
  for (const AtomSphere& a : m.atoms) cov += glm::outerProduct(a.centre, a.centre);
  glm::vec3 axis(0.577f, 0.577f, 0.577f);
  for (int i = 0; i < 100; ++i) axis = glm::normalize(cov * axis);
  m.up_axis = axis;
  return m;
}

template <class F>
static double seconds(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

static void print(const char* what, const WangSet& set, double s) {
  std::printf("%s: %zu tiles, %.2f s, max overhang %.1f Å\n", what, set.tiles.size(), s, set.max_overhang());
  for (const MoleculeDensity& d : set.densities)
    std::printf("  %-12s requested %.4g achieved %.4g (%.1f%%), %zu copies in set\n", d.name.c_str(), d.requested,
                d.achieved, 100.0 * d.achieved / d.requested, d.copies_in_set);
}

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : "/work/shared/data/pdb";
  const float clearance = argc > 2 ? std::stof(argv[2]) : 1.f;
  const int misses = argc > 3 ? std::stoi(argv[3]) : GenerationBudget{}.max_consecutive_failures;
  const MoleculeType lipid = read_pdb(dir + "/lipid_306.pdb", "lipid_306");
  const MoleculeType spike = read_pdb(dir + "/6vxx.pdb", "spike_6vxx");
  const MoleculeType hb = read_pdb(dir + "/4hhb.pdb", "haemoglobin");
  std::setvbuf(stdout, nullptr, _IONBF, 0);
  std::printf("atoms: lipid %zu, spike %zu, haemoglobin %zu; clearance %.2f\n", lipid.atoms.size(), spike.atoms.size(),
              hb.atoms.size(), clearance);

  MembraneTileRequest m;
  m.types = {spike, lipid};
  m.edge = 200.f;
  m.molecules = {{0, 0.5 / (200.0 * 200.0 * 1e-8), 0.f}};
  m.lipids = LipidFill{1, 65.f, 18.f};
  m.budget.clearance = clearance;
  m.budget.max_consecutive_failures = misses;
  WangSet ms;
  const double tm = seconds([&] { ms = make_membrane_tiles(m); });
  print("membrane 200 Å, spike 1 per 2 tiles + lipids 65 Å²", ms, tm);

  SolubleCubeRequest c;
  c.types = {hb};
  c.edge = 250.f;
  c.molecules = {{0, copies_per_um3_from_millimolar(5.0)}};
  c.budget.clearance = clearance;
  c.budget.max_consecutive_failures = misses;
  try {
    WangSet cs;
    const double tc = seconds([&] { cs = make_soluble_cubes(c); });
    print("cubes 250 Å, haemoglobin 5 mM", cs, tc);
  } catch (const nano::InputError& e) {
    std::printf("cubes 250 Å, haemoglobin 5 mM: %s\n", e.what());
  }
  return 0;
}
