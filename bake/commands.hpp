#pragma once
// Each nanobake subcommand lives in its own module and registers itself here.
#include <CLI/CLI.hpp>

namespace nano::bake {
void add_inspect_command(CLI::App& app);     // bake/structure/inspect_command.cpp
void add_check_mesh_command(CLI::App& app);  // bake/mesh/check_mesh_command.cpp
void add_make_mesh_command(CLI::App& app);   // bake/mesh/make_mesh_command.cpp
void add_bake_command(CLI::App& app);        // bake/scene_bake/bake_command.cpp
void add_import_cellpack_command(CLI::App& app);  // bake/cellpack/import_command.cpp
}  // namespace nano::bake
