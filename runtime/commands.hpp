#pragma once
// Each nanoview subcommand lives in its own module and registers itself here.
#include <cstdint>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

namespace nano::view {
void add_validate_command(CLI::App& app);  // runtime/validate_command.cpp
void add_devices_command(CLI::App& app);   // runtime/devices_command.cpp
void add_export_command(CLI::App& app);    // runtime/export_command.cpp
void add_render_command(CLI::App& app);    // runtime/render_command.cpp
void add_verify_command(CLI::App& app);    // runtime/verify_command.cpp
void add_bench_command(CLI::App& app);     // runtime/bench_command.cpp
void add_plot_command(CLI::App& app);      // runtime/plot_command.cpp
void add_pick_command(CLI::App& app);      // runtime/pick_command.cpp
void add_view_command(CLI::App& app);      // runtime/view_command.cpp
// "WxH" → (W, H); InputError naming --size otherwise.
std::pair<std::uint32_t, std::uint32_t> parse_size(const std::string& text);
}  // namespace nano::view
