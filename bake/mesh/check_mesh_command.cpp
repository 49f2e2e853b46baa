// nanobake check-mesh MESH [--json] [--tile-size S]
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "bake/commands.hpp"
#include "bake/mesh/mesh_check.hpp"
#include "bake/mesh/mesh_reader.hpp"

namespace nano::bake {

void add_check_mesh_command(CLI::App& app) {
  struct Arguments {
    std::string mesh;
    bool json = false;
    std::optional<double> tile_size;
  };
  auto args = std::make_shared<Arguments>();
  CLI::App* command = app.add_subcommand(
      "check-mesh",
      "Check that a proxy mesh (OBJ/PLY/OFF) is usable for the membrane shell: closed, manifold, outward, "
      "no degenerate or sliver triangles, UVs in [0,1] without zero-area or flipped triangles; reports seams, "
      "UV distortion, the UV scale k and the replication area. Face indices are 0-based triangles in file "
      "order. Exit 0 when usable, 1 with the list of every problem.");
  command->add_option("mesh", args->mesh, "mesh file (.obj, .ply, .off)")->required();
  command->add_flag("--json", args->json, "print the report as JSON");
  command->add_option("--tile-size", args->tile_size,
                      "world size S of one Wang tile (default k/20: 20 tiles across the unit UV square)")
      ->check(CLI::PositiveNumber);
  command->callback([args] {
    const mesh::ProxyMesh proxy = mesh::read_proxy_mesh(args->mesh);
    mesh::CheckOptions options;
    options.tile_size = args->tile_size;
    const mesh::MeshReport report = mesh::check_mesh(proxy, options);
    const std::string text = args->json ? mesh::report_to_json(report).dump(2) + "\n"
                                        : mesh::report_to_text(report, args->mesh);
    std::fputs(text.c_str(), stdout);
    std::fflush(stdout);
    if (!report.usable()) throw CLI::RuntimeError(1);
  });
}

}  // namespace nano::bake
