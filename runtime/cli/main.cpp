// nanoview: maps a .nup package into Vulkan and renders it with nested ray queries.
#include "common/run_cli.hpp"
#include "runtime/cli/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"nanoview: renders, validates and benchmarks Nanouniverse packages (.nup)", "nanoview"};
  app.require_subcommand(1);
  nano::view::add_validate_command(app);
  nano::view::add_devices_command(app);
  nano::view::add_export_command(app);
  nano::view::add_render_command(app);
  nano::view::add_verify_command(app);
  nano::view::add_bench_command(app);
  nano::view::add_plot_command(app);
  nano::view::add_pick_command(app);
  nano::view::add_view_command(app);
  return nano::run_cli(app, argc, argv);
}
