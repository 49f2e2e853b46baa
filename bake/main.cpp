// nanobake: PDB/mmCIF + meshes + a scene description -> a .nup package.
#include <string>
#include <vector>

#include "bake/commands.hpp"
#include "common/run_cli.hpp"

int main(int argc, char** argv) {
  CLI::App app{"nanobake: bakes molecular scenes into Nanouniverse packages (.nup)", "nanobake"};
  app.require_subcommand(1);
  nano::bake::add_inspect_command(app);
  nano::bake::add_check_mesh_command(app);
  nano::bake::add_make_mesh_command(app);
  nano::bake::add_bake_command(app);
  nano::bake::add_import_cellpack_command(app);
  // `nanobake SCENE.json -o PKG` is short for `nanobake bake SCENE.json -o PKG`.
  std::vector<char*> args(argv, argv + argc);
  static char bake[] = "bake";
  const std::string first = argc > 1 ? argv[1] : "";
  if (first.size() > 5 && first.compare(first.size() - 5, 5, ".json") == 0) args.insert(args.begin() + 1, bake);
  return nano::run_cli(app, static_cast<int>(args.size()), args.data());
}
