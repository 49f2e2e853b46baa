// nanoview: maps a .nup package into Vulkan and renders it with nested ray queries.
#include <cstdio>
#include <exception>

#include "common/error.hpp"
#include "runtime/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"nanoview: renders, validates and benchmarks Nanouniverse packages (.nup)", "nanoview"};
  app.require_subcommand(1);
  nano::view::add_validate_command(app);
  nano::view::add_devices_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const nano::InputError& e) {
    std::fprintf(stderr, "nanoview: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nanoview: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
