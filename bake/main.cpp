// nanobake: PDB/mmCIF + meshes + a scene description -> a .nup package.
#include <cstdio>
#include <exception>

#include "bake/commands.hpp"
#include "common/error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"nanobake: bakes molecular scenes into Nanouniverse packages (.nup)", "nanobake"};
  app.require_subcommand(1);
  nano::bake::add_inspect_command(app);
  nano::bake::add_check_mesh_command(app);
  nano::bake::add_make_mesh_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const nano::InputError& e) {
    std::fprintf(stderr, "nanobake: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nanobake: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
