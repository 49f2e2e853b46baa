// Not a test: times occupancy and keep-masks of the red blood cell (grid_measure [S ...]).
// Solubles: a synthetic haemoglobin-like cube set (radius 32 Å, 5.3 mM ≈ 3.2·10⁶ per µm³).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <thread>

#include "bake/grid/soluble_masks.hpp"
#include "bake/mesh/rbc_mesh.hpp"

using namespace nano;
using Clock = std::chrono::steady_clock;

static double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

int main(int argc, char** argv) {
  const int threads = 2;
  const double shell = 60.0, radius = 32.0, per_cubic_angstrom = 3.2e6 / 1e12;
  auto t0 = Clock::now();
  const mesh::ProxyMesh m = mesh::make_rbc_mesh(argc > 1 && std::atoi(argv[1]) > 1000 ? std::atoi(argv[1]) : 20000);
  const grid::MeshSurface surface(m);
  std::printf("mesh: %zu triangles, surface %.2f s\n", m.triangles.size(), seconds_since(t0));
  for (double S : {200.0, 300.0}) {
    t0 = Clock::now();
    const grid::CoreGrid g = grid::make_core_grid(m, S);
    const grid::BoxOccupancy occ = grid::classify_boxes(surface, g, shell + radius, threads);
    const double t_occ = seconds_since(t0);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> pos(0.0, S);
    const int per_cube = static_cast<int>(per_cubic_angstrom * S * S * S + 0.5);
    std::vector<grid::CubeContents> cubes(16);
    for (auto& c : cubes)
      for (int i = 0; i < per_cube; ++i) c.push_back({{pos(rng), pos(rng), pos(rng)}, radius, 0});
    const grid::CubeRecipe recipe = [](const glm::ivec3& b) { return static_cast<std::uint32_t>((b.x * 7 + b.y * 13 + b.z * 5) & 15); };
    t0 = Clock::now();
    const grid::KeepMasks masks = grid::compute_keep_masks(surface, occ, cubes, recipe, shell, threads);
    const double t_masks = seconds_since(t0);
    t0 = Clock::now();
    const auto copies = grid::represented_copies(occ, cubes, recipe, masks);
    const double t_copies = seconds_since(t0);
    std::printf("S=%.0f dims %dx%dx%d = %llu boxes: outside %llu inside %llu boundary %llu | occupancy %.2f s | "
                "%d molecules/cube, kept %llu dropped %llu, masks %.1f MB, %.2f s | copies %.3g (%.2f s)\n",
                S, g.dims.x, g.dims.y, g.dims.z, (unsigned long long)g.box_count(), (unsigned long long)occ.outside,
                (unsigned long long)occ.inside, (unsigned long long)occ.boundary, t_occ, per_cube,
                (unsigned long long)masks.kept, (unsigned long long)masks.dropped, masks.bytes() / 1e6, t_masks,
                (double)copies[0], t_copies);
  }
}
