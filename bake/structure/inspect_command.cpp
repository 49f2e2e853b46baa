// `nanobake inspect FILE`: reads one structure with the default policy and reports what the
// baker would store for it.
#include <cstdio>
#include <memory>
#include <vector>

#include "bake/commands.hpp"
#include "bake/structure/inspect_report.hpp"
#include "bake/structure/molecule_properties.hpp"
#include "bake/structure/structure_reader.hpp"

namespace nano::bake {
namespace {

struct InspectArguments {
  std::string file;
  bool json = false;
  bool all_models = false;
  bool keep_water = false;
  bool no_hydrogens = false;
  std::vector<double> up;
};

void run_inspect(const InspectArguments& args) {
  structure::SelectionOptions options;
  options.all_models = args.all_models;
  options.keep_water = args.keep_water;
  options.keep_hydrogens = !args.no_hydrogens;
  const structure::Molecule molecule = structure::read_molecule(args.file, options);
  std::optional<glm::dvec3> up;
  if (!args.up.empty()) up = glm::dvec3(args.up[0], args.up[1], args.up[2]);
  const structure::MoleculeProperties properties = structure::compute_molecule_properties(molecule.atoms, up);
  const std::string out = args.json ? structure::inspect_report_json(molecule, properties).dump(2) + "\n"
                                    : structure::inspect_report_text(molecule, properties);
  std::fwrite(out.data(), 1, out.size(), stdout);
}

}  // namespace

void add_inspect_command(CLI::App& app) {
  auto args = std::make_shared<InspectArguments>();
  CLI::App* cmd = app.add_subcommand("inspect", "Read a PDB/mmCIF file (optionally .gz) and summarise the molecule");
  cmd->add_option("file", args->file, "PDB or mmCIF file")->required();
  cmd->add_flag("--json", args->json, "Print JSON instead of text");
  cmd->add_flag("--all-models", args->all_models, "Keep every model, not only the first");
  cmd->add_flag("--keep-water", args->keep_water, "Keep water residues (HOH, WAT, DOD, H2O)");
  cmd->add_flag("--no-hydrogens", args->no_hydrogens, "Drop hydrogen and deuterium atoms");
  cmd->add_option("--up", args->up, "Up axis x y z (default: the axis of largest variance)")
      ->expected(3)
      ->check([](const std::string& s) { return s.empty() ? "empty value" : std::string(); });
  cmd->callback([args] {
    if (!args->up.empty() && args->up[0] == 0.0 && args->up[1] == 0.0 && args->up[2] == 0.0)
      throw CLI::ValidationError("--up", "the up axis must not be the zero vector");
    run_inspect(*args);
  });
}

}  // namespace nano::bake
