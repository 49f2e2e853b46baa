#pragma once
// A cellPACK recipe (cellpack::Recipe) as a Nanouniverse scene (docs/scene.md): each ingredient a
// molecule with an amount, each region a fill — the outside the scene's medium, a compartment's
// interior its soluble, its surface its membrane's proteins on a bilayer — and a report, one line
// per ingredient: what it asked for, what the scene holds and the volume or area that implies, and
// what was not carried over.
// Amounts: a molarity M is M·1000 mM; cellPACK adds nbMol/count to the molarity's copies, so a count
// becomes the concentration it makes in its region (copies / (N_A · volume)); on a surface cellPACK
// reads the molarity per Å² (M · 6.022e-4 copies / Å²), here copies / µm², and a count per the
// surface's area. A principal vector becomes the molecule's `up`; an offset along it its depth.
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "bake/cellpack/recipe.hpp"
#include "bake/cellpack/recipe_reader.hpp"
#include "common/json_document.hpp"

namespace nano::cellpack {

struct ImportOptions {
  std::filesystem::path structures;    // where ingredient structures are found (StructureFolder)
  RecipeReadOptions read;              // --server: the local copy of cellPACK's database
  std::filesystem::path lipid_patch;   // the bilayer every membrane is laid on ("" : surfaces are refused)
  std::filesystem::path scene_folder;  // where the scene is written: its file paths are relative to it
  bool stand_ins = false;              // a missing structure becomes a stand-in from its packing spheres
  double fewest_copies = 0;            // a soluble asking fewer copies in its region is left out, by name
};

struct ImportLine {
  std::string ingredient;  // the recipe's id
  std::string region;      // "outside", "COMPARTMENT interior", "COMPARTMENT surface"
  std::string asked;       // the recipe's amounts
  std::string held;        // the scene's amount and what it implies
  std::string stand_in;    // "" or what stands in for its missing structure (--stand-ins)
  std::vector<std::string> not_carried;
  // What the bake is checked against (copy_number_check): the scene's compartment ("medium" for the
  // outside) and molecule, the copies the recipe asks there (one compartment), and its volume (µm³)
  // or area (µm², surface).
  std::string scene_region, molecule;
  double expected_copies = 0, measure = 0;
  bool surface = false;
  std::string note;  // what the user should know before the bake ("" none)
};

struct ImportResult {
  Json scene;
  std::vector<ImportLine> report;
};

// Throws InputError naming the recipe, the ingredient and what is missing (every missing structure
// at once, with the file names tried).
ImportResult scene_from_recipe(const Recipe& recipe, const ImportOptions& options);

// The report as text, one line per ingredient.
std::string report_text(const Recipe& recipe, const ImportResult& result);

// After the bake: the copies the bake placed per (scene region, molecule) — a compartment's for one
// copy of it, the medium's estimated — against what each ingredient asked, per µm³ or µm². One line
// per ingredient; `off` counts those more than 10 % away, each with what the scene could not hold.
using HeldCopies = std::map<std::pair<std::string, std::string>, double>;
std::string copy_number_check(const ImportResult& result, const HeldCopies& held, int& off);

// The report as JSON (one object per ingredient) for the bake's --report, with the copies placed
// beside those asked where `held` is given.
Json report_json(const ImportResult& result, const HeldCopies* held);

}  // namespace nano::cellpack
