#pragma once
// Shared top level of both executables: parse, run the chosen subcommand, and turn bad input
// into "PROGRAM: error: FILE:WHERE: RULE" with exit status 1 instead of a crash.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

namespace nano {

inline int run_cli(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", app.get_name().c_str(), e.what());
    return 1;
  }
  return 0;
}

}  // namespace nano
