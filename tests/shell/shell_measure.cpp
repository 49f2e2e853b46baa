// Offsets, ownership and timing of the membrane mapping for realistic membranes from the real PDB files
// (not a test; prints one block per scene):
//   shell_measure PDB_DIR [rbc triangles] [rbc R0 in Å]
// Virion: cube-sphere r = 500 Å, spike 6vxx at 0.4 per tile, lipid_306 at 65 Å² per leaflet (±18 Å).
// RBC: Evans–Fung, lipid_306 at 65 Å² plus aquaporin 1j4n (stand-in for band 3) at 10⁶ per cell.
#include <chrono>
#include <cstdio>
#include <string>

#include "bake/mesh/rbc_mesh.hpp"
#include "bake/mesh/sphere_mesh.hpp"
#include "bake/mesh/uv_distortion.hpp"
#include "bake/shell/membrane_mapping.hpp"
#include "bake/shell/shell_offsets.hpp"
#include "bake/structure/molecule_properties.hpp"
#include "bake/structure/structure_reader.hpp"
#include "bake/tiles/tiling_recipe.hpp"
#include "bake/tiles/wang_sets.hpp"

using namespace nano;

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// Heavy atoms about the centroid, up = principal axis (what a reader hands the tile generator).
tiles::MoleculeType read_type(const std::string& path, const std::string& name) {
  structure::SelectionOptions sel;
  sel.keep_hydrogens = false;
  const structure::Molecule mol = structure::read_molecule(path, sel);
  const structure::MoleculeProperties p = structure::compute_molecule_properties(mol.atoms);
  tiles::MoleculeType t{name, {}, float(p.bounding_radius), glm::vec3(p.up)};
  for (const structure::Atom& a : mol.atoms) t.atoms.push_back({glm::vec3(a.position - p.centroid), float(a.radius)});
  return t;
}

void measure(const char* name, const mesh::ProxyMesh& mesh, const tiles::MembraneTileRequest& req) {
  std::printf("== %s: %zu triangles\n", name, mesh.triangles.size());
  double t0 = now();
  const tiles::WangSet set = tiles::make_membrane_tiles(req);
  std::printf("tiles: %zu, %.1f s\n", set.tiles.size(), now() - t0);
  for (const tiles::MoleculeDensity& d : set.densities)
    std::printf("  %-15s r(origin) %.1f Å, achieved %.4g of %.4g per µm²\n", d.name.c_str(),
                shell::molecule_origin_radius(req.types[d.type]), d.achieved, d.requested);
  const double k = mesh::uv_scale(mesh);
  const tiles::TilingRecipe recipe = tiles::make_tiling_recipe(set.colouring, {64, 64, 1}, 3, true);
  t0 = now();
  const shell::MembraneMapping map(mesh, set, recipe, k, req.types);
  std::printf("mapping: k %.1f Å/UV, s %.6g, W×H %d×%d, %.2f s\n", k, map.tile_uv_size(), map.replication_area().x,
              map.replication_area().y, now() - t0);

  // Candidates (every molecule of every replication area) vs owned: how much of the walk is wasted.
  t0 = now();
  size_t candidates = 0, owned = 0;
  for (size_t t = 0; t < map.triangle_count(); ++t) {
    const auto& tm = map.triangle(t);
    for (int j = 0; j < tm.extent.y; ++j)
      for (int i = 0; i < tm.extent.x; ++i)
        candidates += set.tiles[map.tile_at(tm.origin + glm::ivec2(i, j))].instances.size();
    map.for_each_owned_membrane_molecule(t, [&](const shell::OwnedMolecule&) { ++owned; });
  }
  std::printf("enumeration: %zu owned of %zu candidates (%.1f%%), %.2f s\n", owned, candidates,
              100.0 * owned / double(candidates), now() - t0);

  t0 = now();
  const shell::ShellResult r = shell::compute_shell_offsets(map, req.types);
  const double dt = now() - t0;
  float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {0, 0, 0};
  for (const auto& o : r.offsets) {
    if (o.h_plus == 0 && o.h_minus == 0 && o.side == 0) continue;
    const float v[3] = {o.h_plus, o.h_minus, o.side};
    for (int i = 0; i < 3; ++i) lo[i] = std::min(lo[i], v[i]), hi[i] = std::max(hi[i], v[i]);
  }
  const auto& st = r.stats;
  std::printf("offsets: %.2f s; h+ %.1f..%.1f, h- %.1f..%.1f, side %.1f..%.1f Å; fixed (%.1f, %.1f, %.1f)\n", dt,
              lo[0], hi[0], lo[1], hi[1], lo[2], hi[2], r.fixed.h_plus, r.fixed.h_minus, r.fixed.side);
  std::printf("  %zu molecules in %zu triangles; grown %zu (max %d iterations); uncontained %zu; inverted caps %zu; "
              "min cos(n_i, N) %.4f\n",
              st.owned_molecules, st.triangles_with_molecules, st.grown_triangles, st.max_grow_iterations,
              st.uncontained_triangles, st.inverted_caps, st.min_vertex_normal_cos);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: shell_measure PDB_DIR [rbc triangles] [rbc R0 in Å]\n"
                         "  PDB_DIR holds lipid_306.pdb, 6vxx.pdb and 1j4n.pdb (the shared data folder's pdb/)\n");
    return 2;
  }
  const std::string dir = argv[1];
  const int rbc_triangles = argc > 2 ? std::stoi(argv[2]) : 3000;
  mesh::EvansFungShape shape;
  if (argc > 3) shape.r0 = std::stod(argv[3]);
  std::setvbuf(stdout, nullptr, _IONBF, 0);
  const tiles::MoleculeType lipid = read_type(dir + "/lipid_306.pdb", "lipid_306");
  const double per_tile = 1.0 / (200.0 * 200.0 * 1e-8);  // copies per µm² of one copy per 200 Å tile

  tiles::MembraneTileRequest virion;
  virion.types = {read_type(dir + "/6vxx.pdb", "spike_6vxx"), lipid};
  virion.edge = 200.f;
  virion.molecules = {{0, 0.4 * per_tile, 90.f}};
  virion.lipids = tiles::LipidFill{1, 65.f, 18.f};
  measure("virion r=500 Å", mesh::make_sphere_mesh(500, 500.0), virion);

  tiles::MembraneTileRequest rbc;
  rbc.types = {read_type(dir + "/1j4n.pdb", "aquaporin_1j4n"), lipid};
  rbc.edge = 200.f;
  rbc.molecules = {{0, 1e6 / 135.0, 0.f}};  // 10⁶ copies on 135 µm²
  rbc.lipids = tiles::LipidFill{1, 65.f, 18.f};
  measure(("RBC R0=" + std::to_string(int(shape.r0)) + " Å").c_str(), mesh::make_rbc_mesh(rbc_triangles, shape), rbc);
  return 0;
}
