#pragma once
// The command-line options of a recipe import, shared by `nanobake import-cellpack` and by
// `nanobake RECIPE.json -o OUT.nup`, which imports in memory and bakes.
#include <filesystem>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "bake/cellpack/scene_from_recipe.hpp"

namespace nano::cellpack {

struct ImportArguments {
  std::string structures, server, lipid_patch;
  bool stand_ins = false;
  double fewest_copies = 0;
};

// Adds --structures, --server, --lipid-patch, --stand-ins and --fewest-copies to `command` (in a group of their own
// when the command bakes scenes too).
void add_import_options(CLI::App& command, ImportArguments& arguments, bool structures_required, const std::string& group = "");

// The importer's options for `recipe_file`, the scene's paths relative to `scene_folder`; without
// --structures, structures are looked for beside the recipe.
ImportOptions import_options(const ImportArguments& arguments, const std::filesystem::path& recipe_file,
                             const std::filesystem::path& scene_folder);

// True when any import option was given (a scene that is not a recipe refuses them).
bool any_import_option(const ImportArguments& arguments);

}  // namespace nano::cellpack
