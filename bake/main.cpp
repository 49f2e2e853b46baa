// nanobake: PDB/mmCIF + meshes + a scene description -> a .nup package.
#include "bake/commands.hpp"
#include "common/run_cli.hpp"

int main(int argc, char** argv) {
  CLI::App app{"nanobake: bakes molecular scenes into Nanouniverse packages (.nup)", "nanobake"};
  app.require_subcommand(1);
  nano::bake::add_inspect_command(app);
  nano::bake::add_check_mesh_command(app);
  nano::bake::add_make_mesh_command(app);
  return nano::run_cli(app, argc, argv);
}
