// Generation time and achieved densities of realistic sets built from the real PDB files:
//   tiles_measure PDB_DIR [clearance] [misses] [relaxation rounds] [membrane 0/1] [cube seed]
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

// A periodic bilayer patch: each lipid residue (heavy atoms, waters skipped) becomes its own type,
// placed at its centroid; z measured from the mid-plane; the period from CRYST1.
static LipidPatch read_patch(const std::string& path, std::vector<MoleculeType>& types) {
  LipidPatch patch;
  std::ifstream in(path);
  std::string line, current;
  std::vector<glm::vec3> atoms;
  std::vector<std::vector<glm::vec3>> residues;
  const auto flush = [&] {
    if (!atoms.empty()) residues.push_back(atoms);
    atoms.clear();
  };
  while (std::getline(in, line)) {
    if (line.rfind("CRYST1", 0) == 0) {
      patch.period_x = std::stof(line.substr(6, 9));
      patch.period_y = std::stof(line.substr(15, 9));
    }
    if ((line.rfind("ATOM", 0) != 0 && line.rfind("HETATM", 0) != 0) || line.size() < 54) continue;
    if (line.substr(17, 3) == "HOH") continue;
    const std::string element = line.size() >= 78 ? line.substr(76, 2) : "";
    if (element.find('H') != std::string::npos) continue;
    const std::string residue = line.substr(17, 10);
    if (residue != current) flush();
    current = residue;
    atoms.emplace_back(std::stof(line.substr(30, 8)), std::stof(line.substr(38, 8)), std::stof(line.substr(46, 8)));
  }
  flush();
  double mid = 0.0;
  size_t count = 0;
  for (const auto& r : residues)
    for (const glm::vec3& a : r) mid += a.z, ++count;
  mid /= double(count);
  for (const auto& r : residues) {
    glm::vec3 centre(0.f);
    for (const glm::vec3& a : r) centre += a;
    centre /= float(r.size());
    MoleculeType t{"popc_" + std::to_string(patch.lipids.size()), {}, 0.f, {0, 0, 1}};
    for (const glm::vec3& a : r) t.atoms.push_back({a - centre, 1.7f});
    patch.lipids.push_back({uint32_t(types.size()), centre - glm::vec3(0.f, 0.f, float(mid)), glm::quat(1, 0, 0, 0)});
    types.push_back(t);
  }
  return patch;
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
  if (argc < 2) {
    std::fprintf(stderr, "usage: tiles_measure PDB_DIR [clearance] [misses] [relaxation rounds] [membrane 0/1] [cube seed]\n"
                         "  PDB_DIR holds lipid_306.pdb, 6vxx.pdb and 4hhb.pdb (the shared data folder's pdb/)\n");
    return 2;
  }
  const std::string dir = argv[1];
  const float clearance = argc > 2 ? std::stof(argv[2]) : 1.f;
  const int misses = argc > 3 ? std::stoi(argv[3]) : GenerationBudget{}.max_consecutive_failures;
  const int rounds = argc > 4 ? std::stoi(argv[4]) : GenerationBudget{}.relaxation_rounds;
  const bool membrane = argc > 5 ? std::stoi(argv[5]) != 0 : true;
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
  m.budget.relaxation_rounds = rounds;
  if (membrane) {
    WangSet ms;
    const double tm = seconds([&] { ms = make_membrane_tiles(m); });
    print("membrane 200 Å, spike 1 per 2 tiles + lipids 65 Å²", ms, tm);
  }

  // The spike stands at depth 0 with its widest cross-section in the bilayer: it takes ~14% of the
  // lipids of a 200 Å tile pair, so the patch is measured with and without it.
  for (const double spikes_per_tile : {0.5, 0.0}) {
    if (!membrane) break;
    MembraneTileRequest p = m;
    p.types = {spike};
    p.molecules[0].copies_per_um2 = spikes_per_tile / (200.0 * 200.0 * 1e-8);
    p.lipids.reset();
    p.lipid_patch = read_patch(dir + "/popc.pdb", p.types);
    WangSet ps;
    const double tp = seconds([&] { ps = make_membrane_tiles(p); });
    std::printf("membrane 200 Å, spike %.1f per tile + popc.pdb patch (%zu lipids, %.1f x %.1f Å): %zu tiles, %.2f s\n",
                spikes_per_tile, p.lipid_patch->lipids.size(), p.lipid_patch->period_x, p.lipid_patch->period_y,
                ps.tiles.size(), tp);
    double requested = 0.0, achieved = 0.0;
    for (const MoleculeDensity& d : ps.densities)
      if (d.type != 0) requested += d.requested, achieved += d.achieved;
    std::printf("  patch lipids requested %.4g achieved %.4g per µm² (%.1f%%; %.1f Å² per lipid per leaflet)\n",
                requested, achieved, 100.0 * achieved / requested, 2e8 / achieved);
  }

  SolubleCubeRequest c;
  c.seed = argc > 6 ? std::stoull(argv[6]) : 1;
  c.types = {hb};
  c.edge = 250.f;
  c.molecules = {{0, copies_per_um3_from_millimolar(5.0)}};
  c.budget.clearance = clearance;
  c.budget.max_consecutive_failures = misses;
  c.budget.relaxation_rounds = rounds;
  try {
    WangSet cs;
    const double tc = seconds([&] { cs = make_soluble_cubes(c); });
    print("cubes 250 Å, haemoglobin 5 mM", cs, tc);
  } catch (const nano::InputError& e) {
    std::printf("cubes 250 Å, haemoglobin 5 mM: %s\n", e.what());
  }
  return 0;
}
