#pragma once
// The two recipe formats' readers behind read_recipe (recipe_reader.cpp), which parses the file and
// tells the formats apart; what they share about reading other files lives in RecipeFiles.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "bake/cellpack/recipe.hpp"
#include "bake/cellpack/recipe_reader.hpp"
#include "common/json_cursor.hpp"

namespace nano::cellpack {

// The files one read_recipe call opens, counted and bounded; included documents stay alive as long
// as the cursors into them.
class RecipeFiles {
public:
  RecipeFiles(std::filesystem::path recipe, const RecipeReadOptions& options);
  const RecipeReadOptions& options() const { return options_; }
  const std::filesystem::path& folder() const { return folder_; }
  // The document an `include` names, read from the first candidate that exists; `from` is the
  // cursor holding the include's file name (for errors naming what was tried).
  const Json& include(const JsonCursor& from, std::string& file_for_messages);

private:
  std::filesystem::path folder_;
  RecipeReadOptions options_;
  std::filesystem::path recipe_;  // canonical: an include naming it is a cycle
  std::vector<std::unique_ptr<Json>> documents_;
  std::vector<std::unique_ptr<std::string>> names_;
  std::size_t files_read_ = 1;
};

void read_v1(const JsonCursor& root, RecipeFiles& files, Recipe& recipe);
void read_v2(const JsonCursor& root, Recipe& recipe);

// What an ingredient asks for that the model does not carry, said the same way for both formats.
void note_not_carried(Ingredient& ingredient, const std::string& type, const std::string& gradient, bool has_partners,
                      const std::string& packing_mode);

}  // namespace nano::cellpack
