#include "bake/cellpack/recipe_reader.hpp"

#include <algorithm>

#include "bake/cellpack/recipe_formats.hpp"
#include "common/error.hpp"

namespace nano::cellpack {
namespace fs = std::filesystem;

namespace {

// cellPACK's own prefixes for files of its database: the part after them is a path inside it.
std::optional<std::string> server_relative(const std::string& written) {
  for (const std::string prefix : {"autoPACKserver/", "github:"})
    if (written.rfind(prefix, 0) == 0) return written.substr(prefix.size());
  return std::nullopt;
}

std::string tried_list(const std::vector<fs::path>& candidates) {
  std::string s;
  for (const fs::path& p : candidates) s += (s.empty() ? "" : ", ") + p.string();
  return s;
}

}  // namespace

std::vector<fs::path> recipe_file_candidates(const std::string& written, const fs::path& recipe_folder,
                                             const RecipeReadOptions& options) {
  std::vector<fs::path> out;
  const std::optional<std::string> inside = server_relative(written);
  const fs::path relative = fs::path(inside.value_or(written)).lexically_normal();
  if (inside && !options.server_folder.empty()) out.push_back(options.server_folder / relative);
  if (!inside) out.push_back(recipe_folder / relative);
  // Recipes from cellPACK's database name their neighbours by server path; a folder of downloaded
  // files holds them side by side.
  if (relative.has_filename() && (inside || relative.has_parent_path())) out.push_back(recipe_folder / relative.filename());
  return out;
}

RecipeFiles::RecipeFiles(fs::path recipe, const RecipeReadOptions& options)
    : folder_(recipe.parent_path()), options_(options) {
  std::error_code ec;
  recipe_ = fs::weakly_canonical(recipe, ec);
}

const Json& RecipeFiles::include(const JsonCursor& from, std::string& file_for_messages) {
  if (!from.json().is_string()) from.fail("expected an include file name, got " + from.shown());
  const std::string written = from.string();
  const std::vector<fs::path> candidates = recipe_file_candidates(written, folder_, options_);
  const auto found = std::find_if(candidates.begin(), candidates.end(), [](const fs::path& p) {
    std::error_code ec;
    return fs::is_regular_file(p, ec);
  });
  if (found == candidates.end())
    from.fail("include '" + written + "' not found (tried " + tried_list(candidates) + ")" +
              (server_relative(written) && options_.server_folder.empty() ? "; --server FOLDER names a local copy of cellPACK's database" : ""));
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(*found, ec);
  if (canonical == recipe_) from.fail("include '" + written + "' includes itself (a cycle through " + found->string() + ")");
  if (++files_read_ > kMaxRecipeFiles) from.fail("a recipe reads at most " + std::to_string(kMaxRecipeFiles) + " files");
  names_.push_back(std::make_unique<std::string>(found->string()));
  documents_.push_back(std::make_unique<Json>(read_json_file(*found)));
  file_for_messages = *names_.back();
  return *documents_.back();
}

void note_not_carried(Ingredient& in, const std::string& type, const std::string& gradient, bool has_partners,
                      const std::string& packing_mode) {
  if (type == "Grow" || type == "grow" || type == "Actine")
    in.not_carried.push_back("a fibre (type " + type + "): fibres are not carried over");
  if (!gradient.empty()) in.not_carried.push_back("gradient " + gradient + ": copies are spread uniformly");
  if (has_partners) in.not_carried.push_back("partners: copies are placed independently of their partners");
  if (!packing_mode.empty() && packing_mode != "random" && packing_mode != "close" && packing_mode != "gradient")
    in.not_carried.push_back("packing mode " + packing_mode + ": packed at random");
}

bool is_cellpack_recipe(const Json& doc) {
  return doc.is_object() && !doc.contains("format") && (doc.contains("format_version") || doc.contains("recipe"));
}

Recipe read_recipe(const fs::path& file, const RecipeReadOptions& options) { return parse_recipe(read_json_file(file), file, options); }

Recipe parse_recipe(const Json& doc, const fs::path& file, const RecipeReadOptions& options) {
  const std::string name = file.string();
  const JsonCursor root(doc, name);
  if (!doc.is_object()) root.fail("expected a cellPACK recipe object, got " + root.shown());
  Recipe recipe;
  recipe.file = name;
  if (root.has("format_version")) {
    const std::string v = root.required("format_version").json().is_string() ? root.required("format_version").string()
                                                                               : root.required("format_version").json().dump();
    if (v.rfind("2", 0) != 0)
      root.required("format_version").fail("unknown recipe format '" + v + "' (known: v1 without format_version, 2.0, 2.1)");
    read_v2(root, recipe);
  } else if (root.has("recipe")) {
    RecipeFiles files(file, options);
    read_v1(root, files, recipe);
  } else {
    root.fail("not a cellPACK recipe: neither `format_version` (v2) nor `recipe` (v1)");
  }
  return recipe;
}

}  // namespace nano::cellpack
