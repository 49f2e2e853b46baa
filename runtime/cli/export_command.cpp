// `nanoview export PKG --box xmin,ymin,zmin,xmax,ymax,zmax -o FILE.csv|.pdb|.cif`: every atom of the
// package inside a world box, computed by the explicit-instancing oracle (no GPU).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "format/validator.hpp"
#include "runtime/cli/commands.hpp"
#include "runtime/oracle/atom_export.hpp"

namespace nano::cli {
namespace {

oracle::WorldBox parse_box(const std::string& text) {
  double v[6];
  std::istringstream in(text);
  for (int i = 0; i < 6; ++i) {
    if (!(in >> v[i]) || !std::isfinite(v[i]) || (i < 5 && in.get() != ','))
      throw InputError("--box", "", "expected six finite numbers xmin,ymin,zmin,xmax,ymax,zmax, got '" + text + "'");
  }
  if (in >> std::ws, !in.eof()) throw InputError("--box", "", "trailing text after six numbers in '" + text + "'");
  oracle::WorldBox box{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
  for (int a = 0; a < 3; ++a)
    if (box.min[a] > box.max[a]) throw InputError("--box", "", "minimum exceeds maximum on axis " + std::to_string(a));
  return box;
}

}  // namespace

void add_export_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("export", "Write every atom of a package inside a world box (CSV, PDB or mmCIF; no GPU)");
  auto file = std::make_shared<std::string>();
  auto box = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  cmd->add_option("PKG", *file, "package (.nup)")->required();
  cmd->add_option("--box", *box, "world box in Å: xmin,ymin,zmin,xmax,ymax,zmax")->required();
  cmd->add_option("-o,--output", *out, "output file: .csv, .pdb or .cif (written atomically)")->required();
  auto hide = std::make_shared<std::vector<std::string>>();
  cmd->add_option("--hide", *hide, "leave out: medium, a compartment or a molecule type, by name (as render --hide); repeatable");
  cmd->callback([file, box, out, hide] {
    const oracle::WorldBox world = parse_box(*box);
    const oracle::AtomFormat format = oracle::atom_format_of(*out);
    const format::Package package = format::open_validated(*file);
    oracle::ExplicitSceneOptions options;
    options.medium = std::find(hide->begin(), hide->end(), "medium") == hide->end();
    options.visibility = placement::resolve_hidden(package, *hide);
    const oracle::ExplicitScene scene(package, options);
    const oracle::ExportCounts n = oracle::export_atoms(scene, world, *out, format);
    std::printf("%s: %llu copies, %llu atoms\n", out->c_str(), static_cast<unsigned long long>(n.copies),
                static_cast<unsigned long long>(n.atoms));
  });
}

}  // namespace nano::cli
