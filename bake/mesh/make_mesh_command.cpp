// nanobake make-mesh sphere|rbc --triangles N -o FILE.obj [--radius R]
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "bake/commands.hpp"
#include "bake/mesh/obj_writer.hpp"
#include "bake/mesh/rbc_mesh.hpp"
#include "bake/mesh/sphere_mesh.hpp"
#include "common/error.hpp"

namespace nano::bake {

void add_make_mesh_command(CLI::App& app) {
  struct Arguments {
    std::string shape;
    std::optional<int> triangles;
    std::string output;
    double radius = 500.0;
  };
  auto args = std::make_shared<Arguments>();
  CLI::App* command = app.add_subcommand(
      "make-mesh",
      "Generate a proxy mesh with UVs as OBJ. sphere: equal-angle cube-sphere (virion proxy), default 1,452 "
      "triangles. rbc: Evans-Fung biconcave red blood cell in angstrom (diameter 7.82 um = 78,200 A), default "
      "3,000 triangles. The triangle count lands within 25% of --triangles.");
  command->add_option("shape", args->shape, "sphere or rbc")->required()->check(CLI::IsMember({"sphere", "rbc"}));
  command->add_option("--triangles", args->triangles, "target triangle count")->check(CLI::PositiveNumber);
  command->add_option("-o,--output", args->output, "output .obj file")->required();
  command->add_option("--radius", args->radius, "sphere radius in angstrom (default 500, a 100 nm virion)")
      ->check(CLI::PositiveNumber);
  command->callback([args, command] {
    if (args->shape == "rbc" && command->count("--radius") > 0)
      throw InputError("", "--radius", "the red blood cell has a fixed size (Evans-Fung); --radius applies to sphere");
    const mesh::ProxyMesh proxy = args->shape == "sphere"
                                      ? mesh::make_sphere_mesh(args->triangles.value_or(1452), args->radius)
                                      : mesh::make_rbc_mesh(args->triangles.value_or(3000));
    mesh::write_obj(args->output, proxy);
    std::printf("%s: %zu triangles, %zu vertices\n", args->output.c_str(), proxy.triangles.size(), proxy.positions.size());
  });
}

}  // namespace nano::bake
