#pragma once
// Reads a cellPACK recipe file (v1 or v2, told apart by `format_version`) into cellpack::Recipe.
// Recipes are foreign files: keys cellPACK's packer alone uses are passed over, but every value the
// model takes is checked (type, range) and a broken one is an InputError naming the file and key.
// v1 `include` files are read from the recipe's folder, or — for cellPACK's server paths
// (`autoPACKserver/recipes/X.json`, `github:recipes/X.json`) — from `server_folder`/recipes/X.json
// and then beside the recipe. An included file is one ingredient's definition: it includes nothing
// further (one that tries is refused), so the only cycle is the recipe including itself, refused too,
// as is a recipe reading more than kMaxRecipeFiles files.
#include <cstddef>
#include <filesystem>

#include "bake/cellpack/recipe.hpp"
#include "common/json_cursor.hpp"

namespace nano::cellpack {

inline constexpr std::size_t kMaxRecipeFiles = 10000;
// Far above any recipe (cellPACK's largest list a few thousand ingredients, counts up to ~10^7)
// and far below what would make later arithmetic overflow.
inline constexpr double kMaxIngredientCount = 1e12;

struct RecipeReadOptions {
  std::filesystem::path server_folder;  // local copy of cellPACK's database folder ("" none)
};

// A document that is a cellPACK recipe rather than one of our scenes (which carry "format"): it
// has `format_version` (v2) or `recipe` (v1). What `nanobake FILE.json` tells them apart by.
bool is_cellpack_recipe(const Json& doc);

Recipe read_recipe(const std::filesystem::path& file, const RecipeReadOptions& options = {});
// The same for a document already parsed (the fuzzer's entry): `file` names it in errors and is
// where v1 includes are looked for.
Recipe parse_recipe(const Json& doc, const std::filesystem::path& file, const RecipeReadOptions& options = {});

// Where an include or a file a recipe names (`autoPACKserver/...`, `github:...`, a plain relative
// name) is looked for, in order: exported for the importer, which resolves meshes and sphere trees
// the same way.
std::vector<std::filesystem::path> recipe_file_candidates(const std::string& written, const std::filesystem::path& recipe_folder,
                                                          const RecipeReadOptions& options);

}  // namespace nano::cellpack
