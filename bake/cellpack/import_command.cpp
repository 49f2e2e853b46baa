// nanobake import-cellpack RECIPE.json --structures DIR [--server DIR] [--lipid-patch FILE]
//   [--stand-ins] -o SCENE.json [--report FILE]: a cellPACK recipe as a Nanouniverse scene, and the
// report of what each ingredient asked for and what the scene holds.
#include <cstdio>
#include <memory>
#include <string>

#include "bake/cellpack/import_options.hpp"
#include "bake/commands.hpp"
#include "common/atomic_file.hpp"

namespace nano::bake {

void add_import_cellpack_command(CLI::App& app) {
  struct Arguments {
    std::string recipe, output, report;
    cellpack::ImportArguments import;
  };
  auto args = std::make_shared<Arguments>();
  CLI::App* command = app.add_subcommand(
      "import-cellpack",
      "Write a Nanouniverse scene from a cellPACK recipe (v1 recipe versions 1.0-1.1, v2 format 2.0-2.1), with a "
      "report of what each ingredient asked for and what the scene holds (docs/scenes.md, cellPACK recipes)");
  command->add_option("recipe", args->recipe, "cellPACK recipe (.json)")->required();
  cellpack::add_import_options(*command, args->import, true);
  command->add_option("-o,--output", args->output, "scene file to write (.json, written atomically)")->required();
  command->add_option("--report", args->report, "also write the report to this file");
  command->callback([args] {
    const cellpack::ImportOptions options =
        cellpack::import_options(args->import, args->recipe, std::filesystem::path(args->output).parent_path());
    const cellpack::Recipe recipe = cellpack::read_recipe(args->recipe, options.read);
    const cellpack::ImportResult result = cellpack::scene_from_recipe(recipe, options);
    const auto write = [](const std::string& path, const std::string& text) {
      write_file_atomically(path, std::as_bytes(std::span(text.data(), text.size())));
    };
    write(args->output, result.scene.dump(2) + "\n");
    const std::string report = cellpack::report_text(recipe, result);
    if (!args->report.empty()) write(args->report, report);
    std::printf("%s%s: written\n", report.c_str(), args->output.c_str());
  });
}

}  // namespace nano::bake
