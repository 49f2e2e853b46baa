#pragma once
// Each nanoview subcommand lives in its own module and registers itself here.
#include <cstdint>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

namespace nano::cli {
void add_validate_command(CLI::App& app);  // runtime/cli/validate_command.cpp
void add_devices_command(CLI::App& app);   // runtime/cli/devices_command.cpp
void add_export_command(CLI::App& app);    // runtime/cli/export_command.cpp
void add_render_command(CLI::App& app);    // runtime/cli/render_command.cpp
void add_verify_command(CLI::App& app);    // runtime/cli/verify_command.cpp
void add_bench_command(CLI::App& app);     // runtime/cli/bench_command.cpp
void add_plot_command(CLI::App& app);      // runtime/cli/plot_command.cpp
void add_pick_command(CLI::App& app);      // runtime/cli/pick_command.cpp
void add_view_command(CLI::App& app);      // runtime/cli/view_command.cpp
// "WxH" → (W, H); InputError naming --size otherwise.
std::pair<std::uint32_t, std::uint32_t> parse_size(const std::string& text);
}  // namespace nano::cli
