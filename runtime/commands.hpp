#pragma once
// Each nanoview subcommand lives in its own module and registers itself here.
#include <CLI/CLI.hpp>

namespace nano::view {
void add_validate_command(CLI::App& app);  // runtime/validate_command.cpp
void add_devices_command(CLI::App& app);   // runtime/devices_command.cpp
void add_export_command(CLI::App& app);    // runtime/export_command.cpp
}  // namespace nano::view
