// nanoview: maps a .nup package into Vulkan and renders it with nested ray queries.
#include "common/run_cli.hpp"
#include "runtime/cli/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"nanoview: renders, validates and benchmarks Nanouniverse packages (.nup)", "nanoview"};
  app.require_subcommand(1);
  nano::cli::add_validate_command(app);
  nano::cli::add_devices_command(app);
  nano::cli::add_export_command(app);
  nano::cli::add_render_command(app);
  nano::cli::add_verify_command(app);
  nano::cli::add_bench_command(app);
  nano::cli::add_plot_command(app);
  nano::cli::add_pick_command(app);
  nano::cli::add_view_command(app);
  return nano::run_cli(app, argc, argv);
}
