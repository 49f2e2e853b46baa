#include "runtime/commands.hpp"
namespace nano::view { void add_devices_command(CLI::App&) {} }  // placeholder, replaced by the vulkan work
