#include "bake/cellpack/import_options.hpp"

namespace nano::cellpack {

void add_import_options(CLI::App& command, ImportArguments& arguments, bool structures_required, const std::string& group) {
  CLI::Option* structures = command.add_option(
      "--structures", arguments.structures,
      "folder of the ingredients' structures (PDB id or file name, any case, .pdb/.cif/.mmcif/.ent, gzipped or not)" +
          std::string(structures_required ? "" : "; default: the recipe's folder"));
  if (structures_required) structures->required();
  CLI::Option* server = command.add_option("--server", arguments.server,
                                           "local copy of cellPACK's database folder, for autoPACKserver/ and github: paths");
  CLI::Option* patch = command.add_option(
      "--lipid-patch", arguments.lipid_patch,
      "bilayer patch every compartment's membrane is laid on (e.g. data/structures/popc_bilayer.pdb.gz); needed when a "
      "compartment has surface ingredients");
  CLI::Option* stand_ins = command.add_flag(
      "--stand-ins", arguments.stand_ins,
      "draw an ingredient whose structure is missing from its packing spheres (.sph, inline spheres, else its "
      "encapsulating radius), marked STAND-IN in the report, the bake summary and pick");
  CLI::Option* fewest = command.add_option(
      "--fewest-copies", arguments.fewest_copies,
      "leave out (listed in the report) a soluble ingredient asking fewer copies than this in its region: a tiled soluble "
      "may place none of a handful, and the bake then refuses it")->check(CLI::NonNegativeNumber);
  if (!group.empty())
    for (CLI::Option* o : {structures, server, patch, stand_ins, fewest}) o->group(group);
}

ImportOptions import_options(const ImportArguments& arguments, const std::filesystem::path& recipe_file,
                             const std::filesystem::path& scene_folder) {
  ImportOptions options;
  options.structures = arguments.structures.empty() ? recipe_file.parent_path() : std::filesystem::path(arguments.structures);
  if (options.structures.empty()) options.structures = ".";
  options.read.server_folder = arguments.server;
  options.lipid_patch = arguments.lipid_patch;
  options.scene_folder = scene_folder;
  options.stand_ins = arguments.stand_ins;
  options.fewest_copies = arguments.fewest_copies;
  return options;
}

bool any_import_option(const ImportArguments& arguments) {
  return !arguments.structures.empty() || !arguments.server.empty() || !arguments.lipid_patch.empty() || arguments.stand_ins ||
         arguments.fewest_copies > 0;
}

}  // namespace nano::cellpack
