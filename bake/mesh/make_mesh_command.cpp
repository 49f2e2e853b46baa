#include "bake/commands.hpp"
namespace nano::bake { void add_make_mesh_command(CLI::App&) {} }  // placeholder, replaced by the mesh work
