#include "bake/commands.hpp"
namespace nano::bake { void add_check_mesh_command(CLI::App&) {} }  // placeholder, replaced by the mesh work
